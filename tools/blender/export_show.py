"""Export one object's Blender action as an avar show (YAML).

Run headless, from the avar checkout:

    blender -b FILE.blend --python tools/blender/export_show.py -- --out SHOW.yaml \
        [--object NAME] [--action NAME]

Every F-curve of the action becomes one track: object transforms, bone transforms and custom
properties, with each key's time, value, interpolation, Bezier handles and handle types, easing
and its parameters, the curve's extrapolation, auto-smoothing and Cycles modifier.

Channel names (snake_case, so they can be rig channel names as they are):
  ["jaw open"]                           -> jaw_open              (custom property: its name)
  pose.bones["Head.L"]["blink"]          -> head_l_blink          (bone custom property)
  location[0]                            -> location_x            (x, y, z; quaternions w, x, y, z)
  pose.bones["Head.L"].rotation_euler[2] -> head_l_rotation_euler_z
  anything else                          -> its data path in snake_case, then the index
Array properties other than transforms get the index as a suffix (_0, _1, ...); scalars none.

Time: seconds = (frame - scene.frame_start) / (scene.render.fps / scene.render.fps_base), for
keys, handles and elastic periods. Values are in Blender's units (rotations in radians); with
--degrees, Euler rotations and axis-angle angles (values, handles, elastic amplitudes) in degrees.
The show's `duration` is the last key's time, its `name` the action's name. Keys before the
scene's start frame (a scene keyed from frame 0 starts at frame 1) get negative times: avar reads
them, they shape the curve, and the show plays from time 0.

Exit codes: 0 written (warnings, if any, on standard error), 1 nothing written (error on
standard error), 2 bad command line.
"""

import argparse
import json
import math
import os
import re
import struct
import sys

import bpy

SUPPORTED_INTERPOLATIONS = {
    "CONSTANT", "LINEAR", "BEZIER", "SINE", "QUAD", "CUBIC", "QUART", "QUINT", "EXPO", "CIRC", "BACK", "BOUNCE",
    "ELASTIC",
}
EASING_INTERPOLATIONS = SUPPORTED_INTERPOLATIONS - {"CONSTANT", "LINEAR", "BEZIER"}
AXIS_LETTERS = {
    "location": "xyz", "rotation_euler": "xyz", "scale": "xyz",
    "delta_location": "xyz", "delta_rotation_euler": "xyz", "delta_scale": "xyz",
    "rotation_quaternion": "wxyz", "delta_rotation_quaternion": "wxyz", "rotation_axis_angle": "wxyz",
}
QUOTED = r'"((?:[^"\\]|\\.)*)"'
BONE_PROPERTY = re.compile(r'^pose\.bones\[' + QUOTED + r'\]\.(\w+)$')
BONE_CUSTOM = re.compile(r'^pose\.bones\[' + QUOTED + r'\]\[' + QUOTED + r'\]$')
CUSTOM = re.compile(r'^\[' + QUOTED + r'\]$')
PROPERTY = re.compile(r'^(\w+)$')


class ExportError(Exception):
    """A problem that stops the export: the message says what was found and what was expected."""


def warn(message):
    print("warning: " + message, file=sys.stderr)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="blender -b FILE.blend --python tools/blender/export_show.py --",
        description="Write one object's action (every F-curve: object and bone transforms, custom properties) "
                    "as an avar show file.",
        epilog="Examples:\n"
               "  blender -b head.blend --python tools/blender/export_show.py -- --out head.yaml\n"
               "      the active object (or the only animated one) and its current action\n"
               "  blender -b head.blend --python tools/blender/export_show.py -- --out nod.yaml --object Rig --action Nod --degrees\n"
               "      another object, an action it does not currently play, rotations in degrees\n"
               "then: avar sample head.yaml --rate 50   (the curves as CSV)   and   avar check head.yaml --rig RIG\n"
               "Channel names: [\"jaw open\"] -> jaw_open, location[0] -> location_x,\n"
               "pose.bones[\"Head.L\"].rotation_euler[2] -> head_l_rotation_euler_z.\n"
               "Times: (frame - scene start frame) / scene fps. Values in Blender's units (radians).",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True, metavar="SHOW.yaml", help="show file to write")
    parser.add_argument("--object", metavar="NAME",
                        help="object to export (default: the active object if animated, else the only animated one)")
    parser.add_argument("--action", metavar="NAME", help="action to export (default: the object's current action)")
    parser.add_argument("--degrees", action="store_true",
                        help="write Euler rotations and axis-angle angles in degrees instead of radians")
    return parser.parse_args(argv)


def snake(text):
    """Lower-case letters, digits and single underscores: "Head.L" -> head_l, "JawOpen" -> jaw_open."""
    text = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", text)
    text = re.sub(r"[^0-9a-zA-Z]+", "_", text).strip("_").lower()
    return text or "channel"


def unescape(quoted):
    return re.sub(r"\\(.)", r"\1", quoted)


def is_array(obj, data_path):
    try:
        value = obj.path_resolve(data_path)
    except (ValueError, AttributeError):
        return None
    return hasattr(value, "__len__") and not isinstance(value, str)


def channel_name(obj, data_path, index, indices_on_path):
    """The track name of the F-curve data_path[index] (see the module docstring)."""
    def with_index(base, prop):
        array = is_array(obj, data_path)
        if array is None:  # the path does not resolve on this object (e.g. a bone it lacks)
            array = prop in AXIS_LETTERS or indices_on_path != {0}
        if not array:
            return base
        letters = AXIS_LETTERS.get(prop)
        if letters and index < len(letters):
            return base + "_" + letters[index]
        return base + "_" + str(index)

    match = CUSTOM.match(data_path)
    if match:
        return with_index(snake(unescape(match.group(1))), None)
    match = BONE_CUSTOM.match(data_path)
    if match:
        return with_index(snake(unescape(match.group(1))) + "_" + snake(unescape(match.group(2))), None)
    match = BONE_PROPERTY.match(data_path)
    if match:
        return with_index(snake(unescape(match.group(1))) + "_" + match.group(2), match.group(2))
    match = PROPERTY.match(data_path)
    if match:
        return with_index(match.group(1), match.group(1))
    return with_index(snake(data_path), None)


def angle_curve(data_path, index):
    """True when data_path[index] is an angle in radians (Euler rotation, axis-angle angle)."""
    prop = re.split(r"[.\]]", data_path)[-1]
    return prop in ("rotation_euler", "delta_rotation_euler") or (prop == "rotation_axis_angle" and index == 0)


def float32_text(value):
    """Shortest decimal that reads back to the same single-precision float (Blender stores floats)."""
    stored = struct.unpack("f", struct.pack("f", value))[0]
    for digits in range(1, 10):
        text = "%.*g" % (digits, value)
        if struct.unpack("f", struct.pack("f", float(text)))[0] == stored:
            return text
    return repr(value)


def seconds_text(seconds):
    return "%.12g" % seconds


def check_finite(curve_label, what, *numbers):
    for number in numbers:
        if not math.isfinite(number):
            raise ExportError("curve %s: %s is %r; expected a finite number" % (curve_label, what, number))


class Clock:
    """Frames to seconds, as the scene plays them."""

    def __init__(self, scene):
        self.fps = scene.render.fps / scene.render.fps_base
        self.start = scene.frame_start
        self.scene = scene

    def seconds(self, frame):
        return (frame - self.start) / self.fps

    def describe(self):
        render = self.scene.render
        if render.fps_base == 1.0:
            return "%d" % render.fps
        return "%s (%d / %s)" % ("%.6g" % self.fps, render.fps, float32_text(render.fps_base))


def cycles_of(curve, label):
    """The curve's Cycles modifier as YAML flow text, or None; warns about what avar ignores."""
    cycles = None
    for position, modifier in enumerate(curve.modifiers):
        if modifier.mute:
            warn("curve %s: muted %s modifier ignored" % (label, modifier.type.lower()))
            continue
        if modifier.type != "CYCLES":
            warn("curve %s: %s modifier is not supported by avar; ignored (only Cycles is exported)"
                 % (label, modifier.type.lower()))
            continue
        if cycles is not None:
            warn("curve %s: a second Cycles modifier ignored" % label)
            continue
        if position != 0:
            warn("curve %s: the Cycles modifier is not the first modifier; exported as if it were" % label)
        if modifier.use_restricted_range or modifier.use_influence:
            warn("curve %s: the Cycles modifier's restricted frame range and influence are ignored" % label)
        cycles = "{before: %s, after: %s, before_count: %d, after_count: %d}" % (
            modifier.mode_before.lower(), modifier.mode_after.lower(), modifier.cycles_before, modifier.cycles_after)
    return cycles


def key_text(point, clock, label, unit):
    """One key as a YAML flow map; values (and elastic amplitudes) multiplied by `unit`."""
    frame, value = point.co
    (left_frame, left_value), (right_frame, right_value) = point.handle_left, point.handle_right
    check_finite(label, "a key at frame %g" % frame, frame, value, left_frame, left_value, right_frame, right_value)
    value_text = float32_text if unit == 1 else (lambda v: "%.9g" % (v * unit))
    interpolation = point.interpolation
    if interpolation not in SUPPORTED_INTERPOLATIONS:
        raise ExportError("curve %s: interpolation %s at frame %g; expected one of %s"
                          % (label, interpolation, frame, ", ".join(sorted(SUPPORTED_INTERPOLATIONS))))
    fields = [
        "time: " + seconds_text(clock.seconds(frame)),
        "value: " + value_text(value),
        "interpolation: " + interpolation.lower(),
        "left: [%s, %s]" % (seconds_text(clock.seconds(left_frame)), value_text(left_value)),
        "right: [%s, %s]" % (seconds_text(clock.seconds(right_frame)), value_text(right_value)),
        "left_type: " + point.handle_left_type.lower(),
        "right_type: " + point.handle_right_type.lower(),
    ]
    if interpolation in EASING_INTERPOLATIONS:
        fields.append("easing: " + point.easing.lower())
    if interpolation == "BACK":
        fields.append("back: " + float32_text(point.back))
    if interpolation == "ELASTIC":
        # Blender's period is in frames; avar's in seconds (0 keeps Blender's default in both).
        fields.append("amplitude: " + value_text(point.amplitude))
        fields.append("period: " + seconds_text(point.period / clock.fps))
    return "{" + ", ".join(fields) + "}"


def curve_label(curve):
    return "%s[%d]" % (curve.data_path, curve.array_index)


def exported_curves(obj, action):
    """(name, curve) for every F-curve that can be exported, names made unique; warns about the rest."""
    indices = {}
    for curve in action.fcurves:
        indices.setdefault(curve.data_path, set()).add(curve.array_index)
    result, taken = [], {}
    for curve in action.fcurves:
        label = curve_label(curve)
        if curve.mute:
            warn("curve %s is muted; not exported" % label)
            continue
        if len(curve.keyframe_points) == 0:
            warn("curve %s has no keys (baked samples or empty); not exported" % label)
            continue
        name = channel_name(obj, curve.data_path, curve.array_index, indices[curve.data_path])
        if name in taken:
            unique = "%s_%d" % (name, 2)
            suffix = 2
            while unique in taken:
                suffix += 1
                unique = "%s_%d" % (name, suffix)
            warn("curve %s would be named %s like curve %s; named %s" % (label, name, taken[name], unique))
            name = unique
        taken[name] = label
        result.append((name, curve))
    return result


def show_text(source, obj, action, clock, degrees):
    curves = exported_curves(obj, action)
    if not curves:
        raise ExportError("action '%s' has no F-curve with keys to export; expected at least one" % action.name)
    tracks, last_time = [], None
    for name, curve in curves:
        label = curve_label(curve)
        in_degrees = degrees and angle_curve(curve.data_path, curve.array_index)
        unit = 180 / math.pi if in_degrees else 1
        lines = ["  %s:  # %s%s" % (name, label, ", in degrees" if in_degrees else ""),
                 "    extrapolation: " + curve.extrapolation.lower()]
        cycles = cycles_of(curve, label)
        if cycles:
            lines.append("    cycles: " + cycles)
        lines.append("    auto_smoothing: " + ("continuous_acceleration" if curve.auto_smoothing == "CONT_ACCEL" else "none"))
        lines.append("    keys:")
        for point in curve.keyframe_points:
            lines.append("      - " + key_text(point, clock, label, unit))
        end = clock.seconds(curve.keyframe_points[-1].co[0])
        last_time = end if last_time is None else max(last_time, end)
        tracks.append("\n".join(lines))
    duration = last_time
    if duration <= 0:
        duration = clock.seconds(clock.scene.frame_end)
        warn("every key is at or before the start frame; duration set to the scene's frame range, %s s"
             % seconds_text(duration))
        if duration <= 0:
            raise ExportError("the show would last %s s; expected keys or a scene frame range after the start frame"
                              % seconds_text(duration))
    header = [
        "# Exported by tools/blender/export_show.py from Blender %s" % bpy.app.version_string,
        "# source: %s" % source,
        "# object: %s   action: %s   fps: %s   frame_start: %d (time 0)   rotations: %s"
        % (obj.name, action.name, clock.describe(), clock.start, "degrees" if degrees else "radians"),
        "name: " + json.dumps(action.name),
        "duration: " + seconds_text(duration),
        "loop: false",
        "tracks:",
    ]
    return "\n".join(header + tracks) + "\n"


def animated(obj):
    return obj.animation_data is not None and obj.animation_data.action is not None


def chosen_object(name):
    if name is not None:
        obj = bpy.data.objects.get(name)
        if obj is None:
            raise ExportError("no object named '%s'; the file has: %s"
                              % (name, ", ".join(sorted(o.name for o in bpy.data.objects)) or "no objects"))
        return obj
    active = bpy.context.view_layer.objects.active if bpy.context.view_layer else None
    if active is not None and animated(active):
        return active
    candidates = [o for o in bpy.data.objects if animated(o)]
    if len(candidates) == 1:
        return candidates[0]
    if not candidates:
        raise ExportError("no object in the file has an action; expected an animated object (or give --object and --action)")
    raise ExportError("the active object is not animated and several objects are (%s); expected --object NAME"
                      % ", ".join(sorted(o.name for o in candidates)))


def chosen_action(obj, name):
    if name is not None:
        action = bpy.data.actions.get(name)
        if action is None:
            raise ExportError("no action named '%s'; the file has: %s"
                              % (name, ", ".join(sorted(a.name for a in bpy.data.actions)) or "no actions"))
        return action
    if not animated(obj):
        raise ExportError("object '%s' has no current action; expected one, or --action NAME (the file has: %s)"
                          % (obj.name, ", ".join(sorted(a.name for a in bpy.data.actions)) or "no actions"))
    return obj.animation_data.action


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = parse_args(argv)
    try:
        obj = chosen_object(args.object)
        action = chosen_action(obj, args.action)
        text = show_text(bpy.data.filepath or "(unsaved file)", obj, action, Clock(bpy.context.scene), args.degrees)
        try:
            with open(args.out, "w") as out:
                out.write(text)
        except OSError as error:
            raise ExportError("cannot write %s: %s; expected a writable file path" % (args.out, error.strerror))
    except ExportError as error:
        print("error: %s" % error, file=sys.stderr)
        sys.exit(1)
    print("wrote %s: object '%s', action '%s', %d track(s)"
          % (args.out, obj.name, action.name, text.count("\n    keys:")), file=sys.stderr)


if __name__ == "__main__":
    main()
