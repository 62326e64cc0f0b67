#!/usr/bin/env python3
"""`avar sim slcan --pty` as a third-party SLCAN client sees it: python-can's slcan interface
opens the simulated adapter, asks an ODrive axis for its encoder estimate, puts it in closed-loop
control, streams positions and watches the axis get there through its heartbeat and estimates.

Exits 77 (skipped) when python-can is not installed."""
import argparse
import struct
import subprocess
import sys
import time

try:
    import can
except ImportError:
    print("skipped: python-can is not installed (Debian: python3-can)")
    sys.exit(77)


def frames_until(bus, want, timeout=2.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        msg = bus.recv(timeout=max(0.0, end - time.monotonic()))
        if msg is not None and want(msg):
            return msg
    raise AssertionError("no matching frame within %.1f s" % timeout)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--avar", required=True)
    args = parser.parse_args()
    sim = subprocess.Popen([args.avar, "sim", "slcan", "--pty", "--drive", "odrive", "--ids", "3"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        path = sim.stdout.readline().strip()
        assert path.startswith("/dev/pts/"), path
        bus = can.Bus(interface="slcan", channel=path, bitrate=1000000, sleep_after_open=0)
        try:
            node = 3
            heartbeat, estimates = node << 5 | 0x01, node << 5 | 0x09
            # An RTR for the encoder estimates: position 0 turns at power-up.
            bus.send(can.Message(arbitration_id=estimates, is_extended_id=False, is_remote_frame=True, dlc=8))
            msg = frames_until(bus, lambda m: m.arbitration_id == estimates and not m.is_remote_frame)
            pos, vel = struct.unpack("<ff", msg.data)
            assert abs(pos) < 1e-6 and abs(vel) < 1e-6, (pos, vel)
            # Position control, passthrough; then closed loop (state 8), seen in the heartbeat.
            bus.send(can.Message(arbitration_id=node << 5 | 0x0B, is_extended_id=False, data=struct.pack("<ii", 3, 1)))
            bus.send(can.Message(arbitration_id=node << 5 | 0x07, is_extended_id=False, data=struct.pack("<I", 8)))
            frames_until(bus, lambda m: m.arbitration_id == heartbeat and m.data[4] == 8)
            # Stream Set Input Pos 0.25 turns and watch the estimate arrive there.
            end = time.monotonic() + 3.0
            while time.monotonic() < end:
                bus.send(can.Message(arbitration_id=node << 5 | 0x0C, is_extended_id=False,
                                     data=struct.pack("<fhh", 0.25, 0, 0)))
                bus.send(can.Message(arbitration_id=estimates, is_extended_id=False, is_remote_frame=True, dlc=8))
                msg = frames_until(bus, lambda m: m.arbitration_id == estimates and not m.is_remote_frame)
                pos, _ = struct.unpack("<ff", msg.data)
                if abs(pos - 0.25) < 0.01:
                    break
                time.sleep(0.01)
            assert abs(pos - 0.25) < 0.01, pos
            print("ok: python-can %s drove ODrive node 3 to %.3f turns through the simulated SLCAN adapter" % (can.__version__, pos))
        finally:
            bus.shutdown()
    finally:
        sim.terminate()
        sim.wait(timeout=5)
    return 0


if __name__ == "__main__":
    sys.exit(main())
