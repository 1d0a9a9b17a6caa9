#!/usr/bin/env python3
"""Replays a SeaNet wire capture (.seanet) to a UDP port, one datagram per packet, at RATE times a
Micron's beam interval (43 ms): the end-to-end latency measurement of docs/performance.md.
Usage: replay_udp.py CAPTURE.seanet PORT RATE"""
import socket, sys, time
path, port, rate = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
data = open(path, 'rb').read()
packets = []
i = 0
while i < len(data):
    assert data[i:i+1] == b'@'
    length = int.from_bytes(data[i+5:i+7], 'little')
    end = i + 5 + length + 1  # '@', 4 hex, then length bytes from the binary copy, then LF
    packets.append(data[i:end]); i = end
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
start = time.monotonic(); interval = 0.0430 / rate
for k, p in enumerate(packets):
    t = start + k * interval
    while True:
        d = t - time.monotonic()
        if d <= 0: break
        time.sleep(min(d, 0.002))
    s.sendto(p, ('127.0.0.1', port))
print(len(packets), "packets sent in", round(time.monotonic() - start, 2), "s", file=sys.stderr)
