#!/usr/bin/env python3
"""A checkpoint that is whole (its checksum and fingerprint fit) but wrong, for the bad-input
corpus (check.cmake's @CHECKPOINT:...@ token).

    hostile_checkpoint.py MFREE WORK DEST EDIT -- ARGS...

runs `MFREE ARGS...` (a run with checkpoints) in WORK, kills it once its first checkpoint is
in place, as a killed run leaves it, and writes its newest checkpoint to DEST (a folder of
checkpoints for --restart) with one edit, its hash made to fit again:
    ARRAY:INDEX=VALUE   value INDEX of array ARRAY becomes VALUE (a float: 7, nan, -1e300)
    step=VALUE          the step it holds becomes VALUE, its folder named for it
state.bin (io/checkpoint.hpp): the magic, the fingerprint (u64), the step (i64), the number of
arrays (u64), per array its name (u64 length, bytes) and values (u64 count, doubles), then the
FNV-1a hash (u64) of everything before it; little-endian.
"""
import os
import shutil
import signal
import struct
import subprocess
import sys
import time


def fnv1a(data):
    h = 14695981039346656037
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def parse(data):
    """(head: magic and fingerprint, step, [(name, [values])]) of a state.bin."""
    head, (step, count) = data[:16], struct.unpack_from("<qQ", data, 16)
    at, arrays = 32, []
    for _ in range(count):
        (length,) = struct.unpack_from("<Q", data, at)
        name = data[at + 8 : at + 8 + length].decode()
        at += 8 + length
        (n,) = struct.unpack_from("<Q", data, at)
        arrays.append((name, list(struct.unpack_from(f"<{n}d", data, at + 8))))
        at += 8 + 8 * n
    return head, step, arrays


def serialise(head, step, arrays):
    out = bytearray(head) + struct.pack("<qQ", step, len(arrays))
    for name, values in arrays:
        out += struct.pack("<Q", len(name)) + name.encode() + struct.pack(f"<Q{len(values)}d", len(values), *values)
    return bytes(out + struct.pack("<Q", fnv1a(out)))


def first_checkpoint(mfree, work, args):
    """Runs mfree in work until its first checkpoint is in place; the newest step folder."""
    os.makedirs(work, exist_ok=True)
    run = subprocess.Popen([mfree] + args, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    found = []
    while not found:
        if run.poll() is not None:
            sys.exit(f"hostile_checkpoint: the run ended before its first checkpoint:\n{run.stderr.read().decode()}")
        time.sleep(0.01)
        found = [d for r, ds, _ in os.walk(work) for d in ds if d.startswith("step_") and r.endswith(".checkpoints")]
    run.send_signal(signal.SIGKILL)
    run.wait()
    folders = sorted(os.path.join(r, d) for r, ds, _ in os.walk(work) for d in ds
                     if d.startswith("step_") and r.endswith(".checkpoints"))
    return folders[-1]


def main():
    mfree, work, dest, edit, dashes = sys.argv[1:6]
    assert dashes == "--"
    source = first_checkpoint(mfree, work, sys.argv[6:])
    with open(os.path.join(source, "state.bin"), "rb") as f:
        head, step, arrays = parse(f.read())
    target, value = edit.split("=")
    if target == "step":
        step = int(value)
    else:
        name, index = target.split(":")
        values = dict(arrays)[name]
        values[int(index)] = float(value)
    folder = os.path.join(dest, f"step_{step:010d}")
    shutil.copytree(os.path.join(source, "output"), os.path.join(folder, "output"))
    with open(os.path.join(folder, "state.bin"), "wb") as f:
        f.write(serialise(head, step, arrays))
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
