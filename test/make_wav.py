#!/usr/bin/python3
"""Test audio for the tools' end-to-end checks: 16-bit mono WAV files at 48 kHz, from the
standard library only.

    make_wav.py OUT room RT60 DRR   an impulse at 10 ms, then white noise decaying by 60 dB in
                                    RT60 s from 2.6 ms after it, DRR dB under the impulse
    make_wav.py OUT tone HZ         1 s of a tone
    make_wav.py OUT noise           1 s of white noise (no direct peak)
    make_wav.py OUT short           an impulse and 20 ms of decay
    make_wav.py OUT silent          1 s of silence
"""
import math, random, struct, sys, wave
out, kind = sys.argv[1], sys.argv[2]
rate, x = 48000, []
random.seed(3)
if kind == "room":  # room RT60 DRR: an impulse at 10 ms, decaying noise from 2.6 ms after it
    rt60, drr = float(sys.argv[3]), float(sys.argv[4])
    tail = [random.gauss(0, 1) * math.exp(-6.9078 * k / rate / rt60) for k in range(rate)]
    peak = math.sqrt(10 ** (drr / 10) * sum(v * v for v in tail))
    x = [0.0] * 480 + [peak] + [0.0] * 124 + tail
elif kind == "tone":  # tone HZ
    hz = float(sys.argv[3])
    x = [0.3 * math.sin(2 * math.pi * hz * k / rate) for k in range(rate)]
elif kind == "noise":  # white noise, no direct peak
    x = [random.gauss(0, 1) for k in range(rate)]
elif kind == "short":  # an impulse and 20 ms of decay
    x = [1.0] + [random.gauss(0, 0.1) * math.exp(-k / 100) for k in range(960)]
elif kind == "silent":
    x = [0.0] * rate
top = max(1e-9, max(abs(v) for v in x))
with wave.open(out, "wb") as w:
    w.setnchannels(1)
    w.setsampwidth(2)
    w.setframerate(rate)
    w.writeframes(b"".join(struct.pack("<h", int(round(32000 * v / top))) for v in x))
