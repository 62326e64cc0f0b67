#!/usr/bin/env python3
"""Writes nod.bvh: a small hand-made BVH of a head that turns, nods, tilts and talks (4 s, 30 fps).

Y up, Z forward, centimetres, every rotation joint with channels "Zrotation Xrotation Yrotation"
(local rotation Rz * Rx * Ry). Deterministic: run it again and the file is the same.
  python3 examples/mocap/make_nod_bvh.py > examples/mocap/nod.bvh
"""
import math

FPS = 30
SECONDS = 4


def pose(t):
    """Degrees: head yaw (Y), pitch (X, + looks down), roll (Z), jaw opening (X)."""
    yaw = 35 * math.sin(2 * math.pi * t / SECONDS)
    pitch = 10 * math.sin(2 * math.pi * t / 1.6)
    roll = 6 * math.sin(2 * math.pi * t / 2.0)
    jaw = 9 - 9 * math.cos(2 * math.pi * (t - 1.0) / 0.8) if 1.0 <= t <= 3.4 else 0.0  # three words
    return yaw, pitch, roll, jaw


def main():
    print("HIERARCHY")
    print("ROOT Hips")
    print("{")
    print("  OFFSET 0.00 0.00 0.00")
    print("  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation")
    print("  JOINT Neck")
    print("  {")
    print("    OFFSET 0.00 60.00 0.00")
    print("    CHANNELS 3 Zrotation Xrotation Yrotation")
    print("    JOINT Head")
    print("    {")
    print("      OFFSET 0.00 10.00 0.00")
    print("      CHANNELS 3 Zrotation Xrotation Yrotation")
    print("      JOINT Jaw")
    print("      {")
    print("        OFFSET 0.00 -2.00 3.00")
    print("        CHANNELS 3 Zrotation Xrotation Yrotation")
    print("        End Site")
    print("        {")
    print("          OFFSET 0.00 -2.00 7.00")
    print("        }")
    print("      }")
    print("      End Site")
    print("      {")
    print("        OFFSET 0.00 12.00 0.00")
    print("      }")
    print("    }")
    print("  }")
    print("}")
    frames = FPS * SECONDS + 1
    print("MOTION")
    print(f"Frames: {frames}")
    print(f"Frame Time: {1 / FPS:.7f}")
    for i in range(frames):
        yaw, pitch, roll, jaw = pose(i / FPS)
        values = [0, 100, 0, 0, 0, 0,  # hips: standing still
                  0, 0, 0,  # neck
                  roll, pitch, yaw,  # head: Z X Y
                  0, jaw, 0]  # jaw
        print(" ".join(f"{v:.4f}" for v in values))


if __name__ == "__main__":
    main()
