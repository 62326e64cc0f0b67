#!/usr/bin/env python3
"""The device engine's bit identity on one emulated target: runs the verification run's host build
and its build for the target under the target's emulator (simavr for the AVR, qemu-system-arm for
the Cortex-M boards), compares their lines (hashes of every sample of the golden curves and of the
seeded random curves), and prints `TARGET: N samples, M mismatches`. Exit 0 when every line is
equal, 1 on a mismatch or a run that fails, 77 (skip) when the target's compiler or emulator is
missing."""
import argparse
import os
import re
import subprocess
import sys
import time

BOARDS = {"cortex-m3": "lm3s6965evb", "cortex-m0": "microbit"}


def emulator_command(target, emulator, elf):
    if target == "atmega2560":
        return [emulator, "-m", "atmega2560", "-f", "16000000", elf]
    return [emulator, "-M", BOARDS[target], "-nographic", "-semihosting-config", "enable=on,target=native",
            "-kernel", elf]


def clean(text, target):
    """The run's lines: simavr colours UART lines and shows each newline as a '.' before it."""
    lines = []
    for raw in text.splitlines():
        line = re.sub(r"\x1b\[[0-9;]*m", "", raw).strip()
        if target == "atmega2560":
            if not line.endswith("."):
                continue
            line = line[:-1]
        if re.match(r"^(golden|golden-invalid|random|player) \d+ [0-9a-f]{8} \d+$", line) or line.startswith("samples "):
            lines.append(line)
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--host", required=True)
    parser.add_argument("--target", required=True, choices=["atmega2560", "cortex-m3", "cortex-m0"])
    parser.add_argument("--elf", required=True)
    parser.add_argument("--emulator", default="")
    parser.add_argument("--timeout", type=float, default=1400)
    args = parser.parse_args()
    install = ("(scripts/install-deps.sh installs gcc-avr, avr-libc, simavr, gcc-arm-none-eabi and "
               "qemu-system-arm)")
    if not os.path.exists(args.elf):
        print(f"{args.target}: skipped, its cross compiler is not installed {install}")
        return 77
    if not args.emulator or args.emulator.endswith("-NOTFOUND"):
        print(f"{args.target}: skipped, its emulator is not installed {install}")
        return 77
    host = subprocess.run([args.host], capture_output=True, text=True, check=True).stdout.splitlines()
    started = time.monotonic()
    run = subprocess.run(emulator_command(args.target, args.emulator, args.elf), capture_output=True, text=True,
                         timeout=args.timeout, stdin=subprocess.DEVNULL)
    seconds = time.monotonic() - started
    device = clean(run.stdout + run.stderr, args.target)
    summary = host[-1].split()
    samples, violations = int(summary[1]), int(summary[5])
    mismatched_lines = [(h, d) for h, d in zip(host, device) if h != d]
    mismatches = sum(int(h.split()[3]) for h, _ in mismatched_lines if not h.startswith("samples"))
    if len(device) != len(host):
        print(f"{args.target}: the emulated run printed {len(device)} lines, the host {len(host)}; its last: "
              f"{device[-1] if device else '(nothing)'}")
        print((run.stdout + run.stderr)[-2000:])
        return 1
    device_violations = int(device[-1].split()[5])
    print(f"{args.target}: {samples} samples, {mismatches} mismatches ({len(host) - 1} hashed groups, "
          f"{seconds:.1f} s under {os.path.basename(args.emulator)}); player: {device_violations} ticks over a limit")
    for h, d in mismatched_lines[:10]:
        print(f"  host   {h}\n  device {d}")
    return 0 if not mismatched_lines and violations == 0 and device_violations == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
