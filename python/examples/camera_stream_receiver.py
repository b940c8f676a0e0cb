#!/usr/bin/env python3
"""Receives a `camera_stream` component's images (docs/remote.md, "Camera streaming"), as
SimTwo's UDPCam does: datagrams of five little-endian int32 (0x5241, image number, JPEG size,
number of datagrams, this one's index) then up to 512 bytes of the JPEG, reassembled by image
number. Each complete image is written as a JPEG file (standard library only; open them with
any viewer, or decode with Pillow: Image.open(io.BytesIO(jpeg))).

  camera_stream_receiver.py [--port 9898] [--out frames/] [--count N]
"""
import argparse
import os
import socket
import struct

HEADER = struct.Struct("<5i")
IMAGE_ID = 0x5241


def receive(port, count, address="127.0.0.1"):
    """Yields (number, jpeg bytes) for each complete image, `count` of them (0: forever)."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 8 << 20)
    sock.bind((address, port))
    partial = {}  # number -> [size, packets, {index: chunk}]
    done = 0
    while count == 0 or done < count:
        data = sock.recv(65536)
        if len(data) < HEADER.size:
            continue
        ident, number, size, packets, index = HEADER.unpack_from(data)
        if ident != IMAGE_ID or not 0 <= index < packets:
            continue
        entry = partial.setdefault(number, [size, packets, {}])
        entry[2][index] = data[HEADER.size:]
        if len(entry[2]) == packets:
            jpeg = b"".join(entry[2][i] for i in range(packets))
            del partial[number]
            for old in [n for n in partial if n < number]:  # older images will not complete
                del partial[old]
            if len(jpeg) == size:
                done += 1
                yield number, jpeg


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--port", type=int, default=9898)
    parser.add_argument("--out", default="frames")
    parser.add_argument("--count", type=int, default=0, help="images to receive (0: forever)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for number, jpeg in receive(args.port, args.count):
        path = os.path.join(args.out, f"image_{number:06d}.jpg")
        with open(path, "wb") as f:
            f.write(jpeg)
        print(f"{path}: {len(jpeg)} bytes")


if __name__ == "__main__":
    main()
