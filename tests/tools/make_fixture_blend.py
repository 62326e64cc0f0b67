"""Builds the .blend that tests/tools/blender_export_test.py exports, and Blender's own values
of its curves.

Run headless:
    blender -b --factory-startup --python tests/tools/make_fixture_blend.py -- \
        --out DIR/fixture.blend --golden DIR/golden.json

The scene runs at 30000/1001 fps (fps 30, fps_base 1.001) from frame 11, so the exporter's
frame -> seconds conversion is visible: time = (frame - 11) / 29.97002997.

Objects:
- "Figure", an armature (the active object) with action "FigureAction":
  - location[0]: Bezier keys with auto-clamped, vector and free handles, then linear, constant;
  - location[2]: aligned and auto handles, linear extrapolation, no auto-smoothing;
  - rotation_euler[2]: one key per easing family (sine ... elastic) with ease in/out/in-out/auto,
    back's overshoot and elastic's amplitude and period;
  - rotation_euler[0]: a Cycles modifier (before repeat_offset, after mirror, 2 cycles after);
  - scale[1]: a Noise modifier, which avar does not support (the exporter warns);
  - pose.bones["Head.L"].rotation_euler[1] and pose.bones["Head.L"].location[0]: a bone's keys;
  - pose.bones["Head.L"]["blink"]: a bone's custom property;
  - ["jaw open"], ["EyeLid"]: custom properties;
  - empty_display_size: a scalar built-in property.
- "Prop", an empty with its own action "PropAction" (location[1]), and a second action
  "PropAlt" that no object uses.

With --keyed-from-frame-0, another scene instead, as Blender makes one by default and animators
key it: 30 fps from frame 1, object "Head" with action "HeadNod" keyed from frame 0 (one frame
before the scene starts, so at -1/30 s in the show): location[0] (Bezier, auto-clamped) and
["jaw open"] (linear, then Bezier).

golden.json: {"fps": ..., "frame_start": ..., "curves": {"<data_path>[<index>]": {"frames": [...],
"values": [...]}}} with FCurve.evaluate on a half-frame grid from 45 frames before the first
key to 45 frames after the last.
"""

import argparse
import json
import sys

import bpy

FRAME_START = 11
# Golden values reach this far before the first key and after the last: past two 20-frame cycles.
MARGIN_FRAMES = 45


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="make_fixture_blend.py")
    parser.add_argument("--out", required=True, help="the .blend to write")
    parser.add_argument("--golden", required=True, help="JSON of Blender's evaluated curves")
    parser.add_argument("--keyed-from-frame-0", action="store_true",
                        help="the scene keyed from frame 0 (starting at frame 1) instead of the main fixture")
    return parser.parse_args(argv)


def empty_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for action in list(bpy.data.actions):
        bpy.data.actions.remove(action)
    scene = bpy.context.scene
    scene.render.fps = 30
    scene.render.fps_base = 1.001
    scene.frame_start = FRAME_START
    scene.frame_end = 131
    return scene


def make_armature(scene):
    armature = bpy.data.armatures.new("FigureArmature")
    figure = bpy.data.objects.new("Figure", armature)
    scene.collection.objects.link(figure)
    bpy.context.view_layer.objects.active = figure
    bpy.ops.object.mode_set(mode="EDIT")
    bone = armature.edit_bones.new("Head.L")
    bone.head = (0, 0, 0)
    bone.tail = (0, 0, 1)
    bpy.ops.object.mode_set(mode="OBJECT")
    figure["jaw open"] = 0.0
    figure["EyeLid"] = 0.0
    figure.pose.bones["Head.L"]["blink"] = 0.0
    return figure


def keyed_curve(action, data_path, index, keys, group=None):
    """keys: (frame, value, settings) with settings applied to the keyframe after insertion."""
    curve = action.fcurves.new(data_path, index=index, action_group=group or "")
    for frame, value, settings in keys:
        point = curve.keyframe_points.insert(frame, value, options={"FAST"})
        for name, setting in settings.items():
            setattr(point, name, setting)
    curve.update()
    return curve


def set_handles(curve, index, left=None, right=None):
    point = curve.keyframe_points[index]
    if left is not None:
        point.handle_left = left
    if right is not None:
        point.handle_right = right


def animate_figure(figure):
    action = bpy.data.actions.new("FigureAction")
    figure.animation_data_create().action = action

    loc_x = keyed_curve(action, "location", 0, [
        (11, 0.0, {"interpolation": "BEZIER"}),
        (26, 1.5, {"interpolation": "BEZIER", "handle_left_type": "VECTOR", "handle_right_type": "VECTOR"}),
        (41, 0.5, {"interpolation": "BEZIER", "handle_left_type": "FREE", "handle_right_type": "FREE"}),
        (56, 1.0, {"interpolation": "LINEAR"}),
        (71, 2.0, {"interpolation": "CONSTANT"}),
        (86, -1.0, {}),
    ], group="Object Transforms")
    set_handles(loc_x, 2, left=(36.0, 0.9), right=(47.0, -0.2))
    loc_x.update()

    loc_z = keyed_curve(action, "location", 2, [
        (11, 0.0, {"handle_left_type": "AUTO", "handle_right_type": "AUTO"}),
        (31, 1.0, {"handle_left_type": "ALIGNED", "handle_right_type": "ALIGNED"}),
        (51, 0.25, {"handle_left_type": "AUTO", "handle_right_type": "AUTO"}),
    ], group="Object Transforms")
    set_handles(loc_z, 1, left=(25.0, 0.7), right=(36.0, 1.3))
    loc_z.extrapolation = "LINEAR"
    loc_z.auto_smoothing = "NONE"
    loc_z.update()

    easings = [
        (11, 0.0, {"interpolation": "SINE", "easing": "EASE_IN"}),
        (21, 1.0, {"interpolation": "QUAD", "easing": "EASE_OUT"}),
        (31, 0.0, {"interpolation": "CUBIC", "easing": "EASE_IN_OUT"}),
        (41, 1.0, {"interpolation": "QUART", "easing": "AUTO"}),
        (51, 0.0, {"interpolation": "QUINT", "easing": "EASE_IN"}),
        (61, 1.0, {"interpolation": "EXPO", "easing": "EASE_OUT"}),
        (71, 0.0, {"interpolation": "CIRC", "easing": "EASE_IN_OUT"}),
        (81, 1.0, {"interpolation": "BACK", "easing": "EASE_OUT", "back": 2.5}),
        (91, 0.0, {"interpolation": "BOUNCE", "easing": "AUTO"}),
        (101, 1.0, {"interpolation": "ELASTIC", "easing": "EASE_IN_OUT", "amplitude": 0.3, "period": 4.0}),
        (121, 0.0, {"interpolation": "ELASTIC", "easing": "AUTO"}),
        (131, 0.5, {}),
    ]
    keyed_curve(action, "rotation_euler", 2, easings, group="Object Transforms")

    cyc = keyed_curve(action, "rotation_euler", 0, [
        (11, 0.0, {}), (21, 0.5, {}), (31, 0.2, {}),
    ], group="Object Transforms")
    cycles = cyc.modifiers.new("CYCLES")
    cycles.mode_before = "REPEAT_OFFSET"
    cycles.mode_after = "MIRROR"
    cycles.cycles_after = 2

    noisy = keyed_curve(action, "scale", 1, [(11, 1.0, {}), (41, 1.2, {})], group="Object Transforms")
    noisy.modifiers.new("NOISE")

    bone_path = 'pose.bones["Head.L"]'
    keyed_curve(action, bone_path + ".rotation_euler", 1, [
        (11, 0.0, {"interpolation": "LINEAR"}), (41, 0.8, {"interpolation": "BEZIER"}), (71, -0.3, {}),
    ], group="Head.L")
    keyed_curve(action, bone_path + ".location", 0, [(11, 0.1, {}), (31, 0.0, {})], group="Head.L")
    keyed_curve(action, bone_path + '["blink"]', 0, [(11, 0.0, {}), (13, 1.0, {}), (15, 0.0, {})], group="Head.L")

    keyed_curve(action, '["jaw open"]', 0, [
        (11, 0.0, {}), (14, 0.8, {"interpolation": "LINEAR"}), (17, 0.1, {"interpolation": "CONSTANT"}), (23, 0.6, {}),
    ])
    keyed_curve(action, '["EyeLid"]', 0, [(11, 0.0, {}), (21, 1.0, {})])
    keyed_curve(action, "empty_display_size", 0, [(11, 1.0, {}), (21, 2.0, {"interpolation": "LINEAR"}), (31, 1.0, {})])
    return action


def make_prop(scene):
    prop = bpy.data.objects.new("Prop", None)
    scene.collection.objects.link(prop)
    action = bpy.data.actions.new("PropAction")
    prop.animation_data_create().action = action
    keyed_curve(action, "location", 1, [(11, 0.0, {}), (41, 3.0, {})])
    alt = bpy.data.actions.new("PropAlt")
    alt.use_fake_user = True
    keyed_curve(alt, "location", 1, [(11, 5.0, {}), (21, 4.0, {"interpolation": "LINEAR"}), (31, 6.0, {})])
    return prop


def make_keyed_from_frame_0():
    """Blender's default frame range (from 1) with keys from frame 0; returns the scene and action."""
    scene = empty_scene()
    scene.render.fps = 30
    scene.render.fps_base = 1.0
    scene.frame_start = 1
    scene.frame_end = 140
    head = bpy.data.objects.new("Head", None)
    scene.collection.objects.link(head)
    head["jaw open"] = 0.0
    action = bpy.data.actions.new("HeadNod")
    head.animation_data_create().action = action
    keyed_curve(action, "location", 0, [(0, 0.0, {}), (30, 1.0, {}), (140, 0.5, {})])
    keyed_curve(action, '["jaw open"]', 0, [(0, 0.2, {"interpolation": "LINEAR"}), (60, 0.8, {}), (120, 0.0, {})])
    bpy.context.view_layer.objects.active = head
    return scene, action


def golden_of(actions):
    curves = {}
    for action in actions:
        for curve in action.fcurves:
            first, last = curve.range()
            frames = []
            frame = first - MARGIN_FRAMES
            while frame <= last + MARGIN_FRAMES + 1e-9:
                frames.append(frame)
                frame += 0.5
            name = "%s:%s[%d]" % (action.name, curve.data_path, curve.array_index)
            curves[name] = {"frames": frames, "values": [curve.evaluate(f) for f in frames]}
    return curves


def main():
    args = parse_args()
    if args.keyed_from_frame_0:
        scene, action = make_keyed_from_frame_0()
        golden = {"fps": scene.render.fps / scene.render.fps_base, "frame_start": scene.frame_start,
                  "curves": golden_of([action])}
        with open(args.golden, "w") as out:
            json.dump(golden, out)
        bpy.ops.wm.save_as_mainfile(filepath=args.out)
        return
    scene = empty_scene()
    prop = make_prop(scene)
    figure = make_armature(scene)
    figure_action = animate_figure(figure)
    bpy.context.view_layer.objects.active = figure
    render = scene.render
    golden = {
        "fps": render.fps / render.fps_base,
        "frame_start": scene.frame_start,
        "curves": golden_of([figure_action, prop.animation_data.action, bpy.data.actions["PropAlt"]]),
    }
    with open(args.golden, "w") as out:
        json.dump(golden, out)
    bpy.ops.wm.save_as_mainfile(filepath=args.out)


main()
