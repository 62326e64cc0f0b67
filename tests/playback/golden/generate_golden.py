"""Golden curve data from Blender itself.

Run (Blender 3.4 or later, headless):
    blender -b --factory-startup --python tests/playback/golden/generate_golden.py -- --out tests/playback/golden/

Builds one F-curve per case on a custom property of an empty, lets Blender compute every handle
that its type computes (fcurve.update()), evaluates each curve with Blender's own
FCurve.evaluate on a dense frame grid that reaches well before the first and after the last key,
and writes:
  blender_curves.yaml  an avar show: keys, interpolations, easing parameters, handle TYPES, and
                       handles only for free and aligned sides (avar must compute the others);
  blender_curves.csv   `seconds` then one column per channel: Blender's value at each time.
Frames become seconds with the scene's rate, FPS = 24 (so do handle times and elastic periods).
"""
import argparse
import os
import sys

import bpy

FPS = 24
GRID = [f * 0.5 for f in range(-96, 2 * 120 + 1)]  # frames -48 .. 120 in half frames

# Each case: name -> dict(keys=[...], extrapolation=, smoothing=, cycles=)
# A key: (frame, value) plus options: ipo, easing, lt/rt (handle types), left/right (frames,
# value) for free/aligned sides, back, amplitude, period (frames).
CASES = {}


def case(name, keys, extrapolation="CONSTANT", smoothing="NONE", cycles=None):
    CASES[name] = dict(keys=keys, extrapolation=extrapolation, smoothing=smoothing, cycles=cycles)


def k(frame, value, **opts):
    return dict(frame=frame, value=value, **opts)


ZIGZAG = [(0, 0.0), (10, 8.0), (18, 3.0), (30, 12.0), (44, -4.0), (60, 2.0)]


def zig(**opts):
    return [k(f, v, **opts) for f, v in ZIGZAG]


# Interpolations and handle types.
case("constant", zig(ipo="CONSTANT"))
case("linear", zig(ipo="LINEAR"))
case("bezier_auto_clamped", zig(lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"))
case("bezier_auto", zig(lt="AUTO", rt="AUTO"))
case("bezier_vector", zig(lt="VECTOR", rt="VECTOR"))
case("bezier_free", [
    k(0, 0.0, lt="FREE", rt="FREE", left=(-5, -2.0), right=(4, 6.0)),
    k(10, 8.0, lt="FREE", rt="FREE", left=(2, 12.0), right=(25, 0.0)),  # right reaches past the next key: corrected
    k(18, 3.0, lt="FREE", rt="FREE", left=(16, 9.0), right=(22, -3.0)),
    k(30, 12.0, lt="FREE", rt="FREE", left=(29.9, 2.0), right=(30.1, 14.0)),
    k(44, -4.0, lt="FREE", rt="FREE", left=(35, -4.0), right=(50, -4.0)),
])
case("bezier_aligned", [
    k(0, 0.0, lt="ALIGNED", rt="ALIGNED", left=(-4, -3.0), right=(3, 1.0)),
    k(10, 8.0, lt="ALIGNED", rt="AUTO_CLAMPED", left=(6, 2.0)),
    k(18, 3.0, lt="VECTOR", rt="ALIGNED", right=(24, 9.0)),
    k(30, 12.0, lt="ALIGNED", rt="ALIGNED", left=(26, 12.0), right=(36, 18.0)),
    k(44, -4.0, lt="AUTO", rt="ALIGNED", right=(47, 0.0)),
])
case("bezier_mixed_types", [
    k(0, 0.0, lt="VECTOR", rt="AUTO"),
    k(10, 8.0, lt="AUTO_CLAMPED", rt="VECTOR"),
    k(18, 3.0, lt="FREE", rt="AUTO", left=(15, 0.0)),
    k(30, 12.0, lt="AUTO", rt="AUTO"),
    k(44, -4.0, lt="VECTOR", rt="FREE", right=(50, 3.0)),
    k(60, 2.0, lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"),
])
case("smooth_auto", zig(lt="AUTO", rt="AUTO"), smoothing="CONT_ACCEL")
case("smooth_auto_clamped", zig(lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"), smoothing="CONT_ACCEL")
case("smooth_mixed", [
    k(0, 0.0, lt="AUTO", rt="AUTO"), k(10, 8.0, lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"), k(18, 3.0, lt="VECTOR", rt="VECTOR"),
    k(30, 12.0, lt="AUTO", rt="AUTO"), k(44, -4.0, lt="ALIGNED", rt="AUTO", left=(40, -8.0)), k(60, 2.0, lt="AUTO", rt="AUTO"),
], smoothing="CONT_ACCEL")
MONOTONE = [(0, 0.0), (6, 1.0), (12, 10.0), (30, 11.0), (36, 30.0), (60, 31.0)]
UNEVEN = [(0, 0.0), (1, 5.0), (30, -3.0), (31, 8.0), (60, 0.0)]  # neighbours 30x apart: Blender's 5x handle clamp
case("bezier_auto_clamped_monotone", [k(f, v) for f, v in MONOTONE])  # handles clamped against overshoot
case("bezier_auto_monotone", [k(f, v, lt="AUTO", rt="AUTO") for f, v in MONOTONE])
case("bezier_auto_uneven", [k(f, v, lt="AUTO", rt="AUTO") for f, v in UNEVEN])
case("bezier_auto_clamped_uneven", [k(f, v) for f, v in UNEVEN])
case("smooth_auto_clamped_monotone", [k(f, v) for f, v in MONOTONE], smoothing="CONT_ACCEL")
case("smooth_auto_uneven", [k(f, v, lt="AUTO", rt="AUTO") for f, v in UNEVEN], smoothing="CONT_ACCEL")
case("smooth_two_keys", [k(0, 0.0, lt="AUTO", rt="AUTO"), k(30, 10.0, lt="AUTO", rt="AUTO")], smoothing="CONT_ACCEL",
     extrapolation="LINEAR")
case("mixed_interpolations", [
    k(0, 0.0, ipo="LINEAR"), k(10, 8.0, ipo="BEZIER"), k(18, 3.0, ipo="CONSTANT"), k(30, 12.0, ipo="SINE", easing="EASE_IN_OUT"),
    k(44, -4.0, ipo="BEZIER", lt="AUTO", rt="AUTO"), k(60, 2.0, ipo="LINEAR"),
])

# Extrapolation: Blender's slope rules for each kind of end key.
case("extrapolate_linear_linear", zig(ipo="LINEAR"), extrapolation="LINEAR")
case("extrapolate_linear_constant_ends", zig(ipo="CONSTANT"), extrapolation="LINEAR")
case("extrapolate_linear_auto", zig(lt="AUTO", rt="AUTO"), extrapolation="LINEAR")
case("extrapolate_linear_auto_clamped", zig(lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"), extrapolation="LINEAR")
case("extrapolate_linear_vector", zig(lt="VECTOR", rt="VECTOR"), extrapolation="LINEAR")
case("extrapolate_linear_free", [
    k(0, 0.0, lt="FREE", rt="FREE", left=(-6, -3.0), right=(4, 6.0)), k(20, 8.0), k(40, 3.0, lt="FREE", rt="FREE", left=(35, 2.0), right=(46, -2.0)),
], extrapolation="LINEAR")
case("extrapolate_linear_easing", [k(0, 0.0, ipo="QUAD"), k(20, 8.0, ipo="SINE"), k(40, 3.0, ipo="CUBIC")], extrapolation="LINEAR")
case("extrapolate_linear_smooth", zig(lt="AUTO", rt="AUTO"), extrapolation="LINEAR", smoothing="CONT_ACCEL")

# Easing families: one channel each, its keys cycling through AUTO, EASE_IN, EASE_OUT, EASE_IN_OUT.
EASINGS = ["AUTO", "EASE_IN", "EASE_OUT", "EASE_IN_OUT"]
EASE_KEYS = [(0, 0.0), (12, 10.0), (24, 4.0), (36, 9.0), (48, -6.0)]
for family in ["SINE", "QUAD", "CUBIC", "QUART", "QUINT", "EXPO", "CIRC", "BOUNCE"]:
    case("ease_" + family.lower(), [k(f, v, ipo=family, easing=EASINGS[i % 4]) for i, (f, v) in enumerate(EASE_KEYS)])
case("ease_back", [k(f, v, ipo="BACK", easing=EASINGS[i % 4], back=[1.70158, 2.5, 0.8, 3.0, 1.0][i])
                   for i, (f, v) in enumerate(EASE_KEYS)])
case("ease_elastic_defaults", [k(f, v, ipo="ELASTIC", easing=EASINGS[i % 4], amplitude=0.0, period=0.0)
                               for i, (f, v) in enumerate(EASE_KEYS)])
# Amplitudes below and above the change (|change| is 6 .. 15), periods in frames.
case("ease_elastic_params", [k(f, v, ipo="ELASTIC", easing=EASINGS[i % 4], amplitude=[3.0, 20.0, 2.0, 30.0, 1.0][i],
                                  period=[2.0, 5.0, 0.0, 3.5, 1.0][i])
                             for i, (f, v) in enumerate(EASE_KEYS)])

# Cycles modifier (keys span frames 10..30, so the grid covers several cycles each side).
CYC = [(10, 1.0), (16, 6.0), (22, -2.0), (30, 4.0)]


def cyc(**opts):
    return [k(f, v, **opts) for f, v in CYC]


case("cycles_repeat_auto", cyc(lt="AUTO", rt="AUTO"), cycles=("REPEAT", "REPEAT", 0, 0))
case("cycles_repeat_offset_auto_clamped", cyc(lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"), cycles=("REPEAT_OFFSET", "REPEAT_OFFSET", 0, 0))
case("cycles_repeat_smooth", cyc(lt="AUTO", rt="AUTO"), smoothing="CONT_ACCEL", cycles=("REPEAT", "REPEAT", 0, 0))
case("cycles_offset_smooth_clamped", cyc(lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"), smoothing="CONT_ACCEL",
     cycles=("REPEAT_OFFSET", "REPEAT", 0, 0))
case("cycles_mirror", cyc(ipo="LINEAR"), cycles=("MIRROR", "MIRROR", 0, 0))
case("cycles_counts", cyc(lt="AUTO_CLAMPED", rt="AUTO_CLAMPED"), cycles=("REPEAT", "MIRROR", 2, 1))
case("cycles_counts_linear_extrapolation", cyc(ipo="LINEAR"), extrapolation="LINEAR", cycles=("REPEAT_OFFSET", "REPEAT", 1, 2))
case("cycles_after_only", cyc(ipo="QUAD", easing="EASE_OUT"), extrapolation="LINEAR", cycles=("NONE", "REPEAT_OFFSET", 0, 0))
case("cycles_two_keys_smooth", [k(10, 1.0, lt="AUTO", rt="AUTO"), k(30, 4.0, lt="AUTO", rt="AUTO")], smoothing="CONT_ACCEL",
     cycles=("REPEAT_OFFSET", "REPEAT_OFFSET", 0, 0))
case("cycles_smooth_with_a_vector_key", [k(10, 1.0, lt="AUTO", rt="AUTO"), k(16, 6.0, lt="AUTO", rt="AUTO"),
                                         k(22, -2.0, lt="VECTOR", rt="VECTOR"), k(26, 0.0, lt="AUTO", rt="AUTO"),
                                         k(30, 4.0, lt="AUTO", rt="AUTO")],
     smoothing="CONT_ACCEL", cycles=("REPEAT", "REPEAT", 0, 0))
case("cycles_smooth_clamped_monotone", [k(10, 1.0), k(14, 2.0), k(20, 9.0), k(30, 10.0)], smoothing="CONT_ACCEL",
     cycles=("REPEAT_OFFSET", "REPEAT_OFFSET", 0, 0))
case("cycles_vector_ends", [k(10, 1.0, lt="VECTOR", rt="VECTOR"), k(16, 6.0), k(22, -2.0), k(30, 4.0, lt="VECTOR", rt="VECTOR")],
     cycles=("REPEAT", "REPEAT", 0, 0))


def build(obj, action, name, spec):
    obj[name] = 0.0
    fc = action.fcurves.new(data_path='["%s"]' % name)
    fc.keyframe_points.add(len(spec["keys"]))
    for kp, key in zip(fc.keyframe_points, spec["keys"]):
        kp.co = (key["frame"], key["value"])
        kp.interpolation = key.get("ipo", "BEZIER")
        kp.handle_left_type = key.get("lt", "AUTO_CLAMPED")
        kp.handle_right_type = key.get("rt", "AUTO_CLAMPED")
        kp.handle_left = key.get("left", (key["frame"] - 2, key["value"]))
        kp.handle_right = key.get("right", (key["frame"] + 2, key["value"]))
        if "easing" in key:
            kp.easing = key["easing"]
        kp.back = key.get("back", 1.70158)
        kp.amplitude = key.get("amplitude", 0.0)
        kp.period = key.get("period", 0.0)
    fc.extrapolation = spec["extrapolation"]
    fc.auto_smoothing = spec["smoothing"]
    if spec["cycles"]:
        mod = fc.modifiers.new("CYCLES")
        mod.mode_before, mod.mode_after, mod.cycles_before, mod.cycles_after = spec["cycles"]
    fc.update()
    return fc


EASING_FAMILIES = {"SINE", "QUAD", "CUBIC", "QUART", "QUINT", "EXPO", "CIRC", "BACK", "BOUNCE", "ELASTIC"}


def num(x):
    return repr(float(x))


def key_yaml(kp):
    ipo = kp.interpolation
    fields = ["time: %s" % num(kp.co[0] / FPS), "value: %s" % num(kp.co[1]), "interpolation: %s" % ipo.lower()]
    if ipo in EASING_FAMILIES:
        fields.append("easing: %s" % kp.easing.lower())
    if ipo == "BACK":
        fields.append("back: %s" % num(kp.back))
    if ipo == "ELASTIC":
        fields.append("amplitude: %s" % num(kp.amplitude))
        fields.append("period: %s" % num(kp.period / FPS))
    for side, htype, handle in (("left", kp.handle_left_type, kp.handle_left), ("right", kp.handle_right_type, kp.handle_right)):
        fields.append("%s_type: %s" % (side, htype.lower()))
        if htype in ("FREE", "ALIGNED"):
            fields.append("%s: [%s, %s]" % (side, num(handle[0] / FPS), num(handle[1])))
    return "      - {" + ", ".join(fields) + "}"


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", required=True)
    out = parser.parse_args(argv).out
    os.makedirs(out, exist_ok=True)

    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    obj = bpy.data.objects.new("golden", None)
    scene.collection.objects.link(obj)
    obj.animation_data_create()
    action = bpy.data.actions.new("golden")
    obj.animation_data.action = action
    curves = {name: build(obj, action, name, spec) for name, spec in CASES.items()}

    last_frame = max(kp.co[0] for fc in curves.values() for kp in fc.keyframe_points)
    lines = ["# Generated by generate_golden.py with Blender %s (scene at %d fps); do not edit." % (bpy.app.version_string, FPS),
             "name: blender-golden", "duration: %s" % num(last_frame / FPS + 1), "tracks:"]
    for name, fc in curves.items():
        spec = CASES[name]
        lines.append("  %s:" % name)
        lines.append("    extrapolation: %s" % spec["extrapolation"].lower())
        lines.append("    auto_smoothing: %s" % ("continuous_acceleration" if spec["smoothing"] == "CONT_ACCEL" else "none"))
        if spec["cycles"]:
            before, after, nb, na = spec["cycles"]
            lines.append("    cycles: {before: %s, after: %s, before_count: %d, after_count: %d}" % (before.lower(), after.lower(), nb, na))
        lines.append("    keys:")
        lines.extend(key_yaml(kp) for kp in fc.keyframe_points)
    with open(os.path.join(out, "blender_curves.yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")

    with open(os.path.join(out, "blender_curves.csv"), "w") as f:
        f.write("seconds," + ",".join(curves) + "\n")
        for frame in GRID:
            f.write(",".join([num(frame / FPS)] + ["%.9g" % fc.evaluate(frame) for fc in curves.values()]) + "\n")
    print("wrote %d curves x %d samples to %s" % (len(curves), len(GRID), out))


main()
