#!/usr/bin/env python3
"""Load test of `vivae view` (docs/benchmarks.md, "Viewer under load").

Starts `vivae view` on a free loopback port, opens PAGES WebSocket pages that
step their robots for SECONDS, and meanwhile asks for REFUSED further pages,
which must all be refused with 503 while every slot is taken. Prints the
server's peak memory (VmHWM) and CPU time, the CPU time it spends after the
pages have closed (their work must stop with them), and the refused count.

Bounded: loopback only, a fixed number of connections, a fixed duration, and
a hard deadline after which the server is killed. Python 3 standard library
only (a minimal WebSocket client is below).

Usage: scripts/view-load.py [--vivae PATH] [--source PATH] [--pages 8]
       [--refused 200] [--seconds 30] [--high]
"""

import argparse
import asyncio
import base64
import json
import os
import re
import struct
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TICK = os.sysconf("SC_CLK_TCK")
PAGE = os.sysconf("SC_PAGE_SIZE")


def proc_status(pid):
    """(VmRSS, VmHWM) of `pid` in bytes."""
    fields = {}
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                fields[key] = int(value.split()[0]) * 1024
    return fields["VmRSS"], fields["VmHWM"]


def cpu_seconds(pid):
    """User + system CPU time `pid` has used, in seconds (all its threads)."""
    with open(f"/proc/{pid}/stat") as f:
        after = f.read().rsplit(")", 1)[1].split()
    # Fields 14 and 15 of stat (utime, stime); `after` starts at field 3.
    return (int(after[11]) + int(after[12])) / TICK


async def handshake(port):
    """Opens a WebSocket to the viewer; (HTTP status, reader, writer)."""
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    key = base64.b64encode(os.urandom(16)).decode()
    writer.write(
        (
            f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
            "Upgrade: websocket\r\nConnection: Upgrade\r\n"
            f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n"
        ).encode()
    )
    await writer.drain()
    status = int((await reader.readline()).split()[1])
    while (await reader.readline()) not in (b"\r\n", b""):
        pass
    return status, reader, writer


def frame(opcode, payload):
    """A masked client frame (clients must mask)."""
    mask = os.urandom(4)
    n = len(payload)
    if n < 126:
        head = struct.pack("!BB", 0x80 | opcode, 0x80 | n)
    elif n < 65536:
        head = struct.pack("!BBH", 0x80 | opcode, 0x80 | 126, n)
    else:
        head = struct.pack("!BBQ", 0x80 | opcode, 0x80 | 127, n)
    body = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
    return head + mask + body


async def read_frame(reader):
    """(opcode, payload) of the next server frame (unmasked)."""
    b0, b1 = await reader.readexactly(2)
    n = b1 & 0x7F
    if n == 126:
        (n,) = struct.unpack("!H", await reader.readexactly(2))
    elif n == 127:
        (n,) = struct.unpack("!Q", await reader.readexactly(8))
    return b0 & 0x0F, await reader.readexactly(n)


class Page:
    """One page: reads everything the server sends, answers pings, and steps."""

    def __init__(self, port, high):
        self.port, self.high = port, high
        self.frames = self.errors = self.received = 0
        self.ready = asyncio.Event()

    async def run(self, until):
        status, reader, writer = await handshake(self.port)
        if status != 101:
            raise RuntimeError(f"page refused with {status}")
        send = lambda text: writer.write(frame(1, text.encode()))  # noqa: E731
        listen = asyncio.create_task(self.listen(reader, writer))
        if self.high:
            send('{"type":"resolution","sensors":"64x128","neurons":"20x20"}')
        send('{"type":"play"}')
        send('{"type":"speed","value":200}')
        while time.monotonic() < until:
            send('{"type":"step","n":10000}')  # refused when over the work bound
            send('{"type":"step","n":25}')
            await writer.drain()
            await asyncio.sleep(0.05)
        writer.write(frame(8, b""))
        await writer.drain()
        writer.close()
        listen.cancel()

    async def listen(self, reader, writer):
        try:
            while True:
                opcode, payload = await read_frame(reader)
                self.received += len(payload)
                if opcode == 9:
                    writer.write(frame(10, payload))
                elif opcode == 8:
                    return
                elif opcode == 1:
                    kind = json.loads(payload).get("type")
                    self.frames += kind == "frame"
                    self.errors += kind == "error"
                    if kind == "info":
                        self.ready.set()
        except (asyncio.IncompleteReadError, ConnectionError):
            return


async def refused_attempt(port):
    """Status of one more page's WebSocket request (closed at once)."""
    try:
        status, _, writer = await handshake(port)
        writer.close()
        return status
    except (ConnectionError, asyncio.IncompleteReadError, ValueError, IndexError):
        return 0


async def load(args, port, pid):
    until = time.monotonic() + args.seconds
    pages = [Page(port, args.high) for _ in range(args.pages)]
    tasks = [asyncio.create_task(p.run(until)) for p in pages]
    await asyncio.wait_for(asyncio.gather(*(p.ready.wait() for p in pages)), 60)
    statuses = await asyncio.gather(*(refused_attempt(port) for _ in range(args.refused)))
    peak_rss = 0
    while not all(t.done() for t in tasks):
        peak_rss = max(peak_rss, proc_status(pid)[0])
        await asyncio.sleep(0.2)
    for t in tasks:
        t.result()
    return pages, statuses, peak_rss


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vivae", default=os.path.join(
        os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "vivae"))
    ap.add_argument("--source", default=os.path.join(
        ROOT, "crates/vivae/tests/data/paper-champion.json"))
    ap.add_argument("--pages", type=int, default=8)
    ap.add_argument("--refused", type=int, default=200)
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--high", action="store_true",
                    help="pages at the highest resolution (64x128 sensors, 20x20 neurons)")
    args = ap.parse_args()
    server = subprocess.Popen(
        [args.vivae, "view", args.source, "--port", "0", "--host", "127.0.0.1",
         "--max-viewers", str(args.pages)],
        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        port = int(re.search(r":(\d+)/", server.stdout.readline()).group(1))
        idle_rss = proc_status(server.pid)[0]
        cpu0, t0 = cpu_seconds(server.pid), time.monotonic()
        pages, statuses, peak_rss = asyncio.run(
            asyncio.wait_for(load(args, port, server.pid), args.seconds + 120))
        cpu1, t1 = cpu_seconds(server.pid), time.monotonic()
        time.sleep(3)
        cpu2, t2 = cpu_seconds(server.pid), time.monotonic()
        rss_after, hwm = proc_status(server.pid)
    finally:
        server.kill()
        server.wait()
    mib = 1 << 20
    print(f"pages: {args.pages} ({'64x128/20x20' if args.high else 'the source’s resolution'}),"
          f" {args.seconds:.0f} s, {sum(p.frames for p in pages)} frames,"
          f" {sum(p.errors for p in pages)} error replies,"
          f" {sum(p.received for p in pages) / mib:.1f} MiB sent to them")
    print(f"refused: {statuses.count(503)} of {args.refused} further pages got 503"
          f" (other answers: {sorted(set(s for s in statuses if s != 503))})")
    print(f"server memory: {idle_rss / mib:.1f} MiB idle, peak {hwm / mib:.1f} MiB (VmHWM;"
          f" sampled RSS peak {peak_rss / mib:.1f} MiB), {rss_after / mib:.1f} MiB after")
    print(f"server CPU: {cpu1 - cpu0:.1f} s in {t1 - t0:.1f} s of load"
          f" ({(cpu1 - cpu0) / (t1 - t0):.2f} cores),"
          f" {cpu2 - cpu1:.2f} s in the {t2 - t1:.1f} s after the pages closed")
    return 0 if statuses.count(503) == args.refused else 1


if __name__ == "__main__":
    sys.exit(main())
