#!/usr/bin/env python3
"""Writes golden.json: an independent (Python) rendering of docs/protocol.md, so the C++
codec is checked against something it did not produce. Re-run after a deliberate layout
change and review the diff: `python3 protocol/xy/vectors/make_vectors.py`."""
import json, os

def crc16(data: bytes) -> int:  # CRC-16/CCITT-FALSE
    c = 0xFFFF
    for b in data:
        c ^= b << 8
        for _ in range(8):
            c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c

def data6(v: int) -> str:
    return "-%05d" % -v if v < 0 else "%06d" % v

def command(seq, x, y, subs=()):
    subs = list(subs) + [(0, 0)] * (4 - len(subs))
    payload = "%03d" % seq + "%02d" % x[0] + data6(x[1]) + "%02d" % y[0] + data6(y[1])
    payload += "".join("%02d%02d" % s for s in subs)
    return ">" + payload + "%04X" % crc16(payload.encode()) + ";"

def echo(seq, x, y, packets=()):
    packets = list(packets) + [(0, 0, 0)] * (4 - len(packets))
    payload = "%03d" % seq + "%02d" % x[0] + data6(x[1]) + "%02d" % y[0] + data6(y[1])
    payload += "".join("%02d%02d" % (p[0], p[1]) + data6(p[2]) for p in packets)
    return "<" + payload + "%04X" % crc16(payload.encode()) + ";"

def cmd_expect(seq, x, y, subs=()):
    subs = list(subs) + [(0, 0)] * (4 - len(subs))
    return {"seq": seq, "x": list(x), "y": list(y), "subs": [list(s) for s in subs]}

def echo_expect(seq, x, y, packets=()):
    packets = list(packets) + [(0, 0, 0)] * (4 - len(packets))
    return {"seq": seq, "x": list(x), "y": list(y), "subs": [list(p) for p in packets]}

def recrc(frame: str) -> str:
    """Keeps a deliberately broken payload's CRC right, so the error under test is the one reported."""
    end = len(frame) - 5
    return frame[:end] + "%04X" % crc16(frame[1:end].encode()) + frame[end + 4:]

commands = []
def addc(name, readable, seq, x, y, subs=()):
    commands.append({"name": name, "readable": readable, "bytes": command(seq, x, y, subs),
                     "expect": cmd_expect(seq, x, y, subs)})

addc("keep-alive", "seq=0 x=nop y=nop", 0, (0, 0), (0, 0))
addc("stop X, goto Y (thesis example)", "seq=1 x=stop y=goto:20000", 1, (1, 0), (3, 20000))
addc("jog + fast, battery", "seq=2 x=jog:+:fast y=nop sub=battery", 2, (2, 2), (0, 0), [(1, 0)])
addc("jog - slow on Y", "seq=3 x=nop y=jog:-:slow", 3, (0, 0), (2, -1))
addc("relative move negative", "seq=998 x=move:-99999 y=move:999999", 998, (4, -99999), (4, 999999))
addc("home both, four subscribers", "seq=999 x=home y=home sub=encoder:0 sub=encoder:1 sub=drv_lo:1 sub=link:2",
     999, (5, 0), (5, 0), [(5, 0), (5, 1), (6, 1), (9, 2)])
addc("set accel 20 mm/s^2", "seq=10 x=accel:20000 y=nop sub=param:0", 10, (8, 20000), (0, 0), [(8, 0)])
addc("currents", "seq=11 x=irun:31 y=ihold:0", 11, (13, 31), (14, 0))
addc("unit commands", "seq=12 x=sleep y=save", 12, (15, 0), (17, 0))
addc("mechanics", "seq=13 x=pitch:2000 y=usteps:256 sub=temp sub=rotation", 13, (10, 2000), (12, 256), [(3, 0), (4, 0)])

base = command(1, (1, 0), (3, 20000))
def flip(s, i, ch):
    return s[:i] + ch + s[i + 1:]
invalid_commands = [
    {"name": "empty", "bytes": "", "error": "bad_length", "offset": 0},
    {"name": "one byte short", "bytes": base[:-1], "error": "bad_length", "offset": 40},
    {"name": "one byte long", "bytes": base + ";", "error": "bad_length", "offset": 41},
    {"name": "echo start on a command", "bytes": flip(base, 0, "<"), "error": "bad_start", "offset": 0},
    {"name": "newline instead of end", "bytes": flip(base, 40, "\n"), "error": "bad_end", "offset": 40},
    {"name": "letter in seq", "bytes": flip(base, 2, "A"), "error": "bad_char", "offset": 2},
    {"name": "plus sign in data", "bytes": flip(base, 14, "+"), "error": "bad_char", "offset": 14},
    {"name": "minus not first", "bytes": flip(base, 16, "-"), "error": "bad_char", "offset": 16},
    {"name": "negative zero", "bytes": recrc(command(1, (1, 0), (0, 0))[:14] + "-00000" + command(1, (1, 0), (0, 0))[20:]),
     "error": "bad_char", "offset": 14},
    {"name": "lower-case hex CRC", "bytes": base[:36] + base[36:40].lower() + ";", "error": "bad_char", "offset": 36},
    {"name": "CRC off by one", "bytes": base[:36] + "%04X" % ((int(base[36:40], 16) + 1) & 0xFFFF) + ";",
     "error": "bad_crc", "offset": 36},
    {"name": "digit changed, CRC kept", "bytes": flip(base, 19, "1"), "error": "bad_crc", "offset": 36},
    {"name": "X and Y swapped, CRC kept", "bytes": base[:4] + base[12:20] + base[4:12] + base[20:], "error": "bad_crc", "offset": 36},
    {"name": "unknown command 26", "bytes": command(1, (26, 0), (0, 0)), "error": "unknown_command", "offset": 4},
    {"name": "unknown command 99 on Y", "bytes": command(1, (0, 0), (99, 0)), "error": "unknown_command", "offset": 12},
    {"name": "goto negative", "bytes": command(1, (3, -1), (0, 0)), "error": "data_out_of_range", "offset": 6},
    {"name": "DummyData not zero", "bytes": command(1, (0, 0), (1, 5)), "error": "data_out_of_range", "offset": 14},
    {"name": "jog level 3", "bytes": command(1, (2, 3), (0, 0)), "error": "data_out_of_range", "offset": 6},
    {"name": "unknown subscriber", "bytes": command(1, (0, 0), (0, 0), [(0, 0), (42, 0)]), "error": "unknown_subscriber", "offset": 24},
    {"name": "encoder axis 2", "bytes": command(1, (0, 0), (0, 0), [(5, 2)]), "error": "arg_out_of_range", "offset": 22},
    {"name": "empty slot with argument", "bytes": command(1, (0, 0), (0, 0), [(0, 1)]), "error": "arg_out_of_range", "offset": 22},
]

echoes = []
def adde(name, seq, x, y, packets=()):
    echoes.append({"name": name, "bytes": echo(seq, x, y, packets), "expect": echo_expect(seq, x, y, packets)})
adde("both charger blocked (thesis Obr. 8-4)", 5, (8, 12000), (8, 34000))
adde("moving with subscribers", 2, (1, 1500), (0, 0), [(1, 0, 3712), (3, 0, -5250)])
adde("rejected: bad crc at 36", 1, (14, 436), (14, 436))
adde("four packets", 999, (4, 999999), (6, -99999), [(5, 0, 1), (5, 1, 2), (7, 1, 65535), (9, 3, 999999)])
ebase = echo(5, (8, 12000), (8, 34000))
invalid_echoes = [
    {"name": "command start on an echo", "bytes": flip(ebase, 0, ">"), "error": "bad_start", "offset": 0},
    {"name": "unknown status", "bytes": echo(5, (16, 0), (0, 0)), "error": "unknown_status", "offset": 4},
    {"name": "battery above range", "bytes": echo(5, (0, 0), (0, 0), [(1, 0, 100000)]), "error": "data_out_of_range", "offset": 24},
    {"name": "CRC wrong", "bytes": flip(ebase, 9, "9"), "error": "bad_crc", "offset": 60},
]

a = commands[1]["bytes"]; b = commands[2]["bytes"]; c = commands[3]["bytes"]
streams = [
    {"name": "three frames back to back", "bytes": a + b + c,
     "events": [{"offset": 0, "error": "none"}, {"offset": 41, "error": "none"}, {"offset": 82, "error": "none"}],
     "rejected_bytes": 0},
    {"name": "line noise before and between", "bytes": "xx\r\n" + a + "\n;;12" + b,
     "events": [{"offset": 4, "error": "none"}, {"offset": 50, "error": "none"}], "rejected_bytes": 9},
    {"name": "lost byte costs one frame", "bytes": a[:10] + a[11:] + b,
     "events": [{"offset": 0, "error": "bad_length", "at": 39}, {"offset": 40, "error": "none"}], "rejected_bytes": 40},
    {"name": "truncated frame then a new start", "bytes": a[:20] + b,
     "events": [{"offset": 0, "error": "bad_length", "at": 20}, {"offset": 20, "error": "none"}], "rejected_bytes": 20},
    {"name": "corrupted frame is rejected whole", "bytes": flip(a, 7, "9") + b,
     "events": [{"offset": 0, "error": "bad_crc", "at": 36}, {"offset": 41, "error": "none"}], "rejected_bytes": 41},
    {"name": "extra byte inside a frame", "bytes": a[:10] + "5" + a[10:] + b,
     "events": [{"offset": 0, "error": "bad_end", "at": 40}, {"offset": 42, "error": "none"}], "rejected_bytes": 42},
]

crc_checks = [{"input": "123456789", "crc": "29B1"}, {"input": "", "crc": "FFFF"}, {"input": "A", "crc": "B915"}]

out = {"about": "Golden vectors for docs/protocol.md, written by make_vectors.py (independent of the C++ codec).",
       "crc16_ccitt_false": crc_checks, "commands": commands, "invalid_commands": invalid_commands,
       "echoes": echoes, "invalid_echoes": invalid_echoes, "command_streams": streams}
here = os.path.dirname(os.path.abspath(__file__))
with open(os.path.join(here, "golden.json"), "w") as f:
    json.dump(out, f, indent=1)
    f.write("\n")
# Seed corpora: each valid and invalid frame, one small file each. The stream_framer target
# reads a chunk size and the dispatch target a handler mask from the first byte, so their
# seeds carry that byte in front.
root = os.path.dirname(os.path.dirname(here))
def write_corpus(target, blobs):
    d = os.path.join(root, "fuzz", "corpus", target)
    os.makedirs(d, exist_ok=True)
    for old in os.listdir(d):
        if old.startswith("golden-"):
            os.remove(os.path.join(d, old))
    for i, blob in enumerate(blobs):
        with open(os.path.join(d, "golden-%02d" % i), "wb") as f:
            f.write(blob)
enc = lambda it: it["bytes"].encode("latin-1")
write_corpus("frame_parser", [enc(it) for it in commands + invalid_commands + echoes + invalid_echoes])
write_corpus("stream_framer", [bytes([i % 97]) + enc(it) for i, it in enumerate(streams + commands[:3])] +
             [bytes([5]) + b"".join(enc(e) for e in echoes)])
# Mask 0x83 removes the handlers of IDs 3, 11 (goto, steps): the thesis example then has X
# handled and Y not, which must run neither.
write_corpus("dispatch", [b"\x00" + enc(it) for it in commands + invalid_commands] +
             [b"\x83" + enc(commands[1]) + enc(commands[2]), b"\x84" + enc(commands[4])])
