#!/usr/bin/python3
"""Writes the example records of tests/data/instruments/: one record of 200 samples (two
sines at 100 MS/s from t = 0) as a plain `t,V` CSV and in the layout of each oscilloscope
export stengmc reads (docs/records.md, io/instrument_csv.cpp: which document each follows).
InstrumentRecords.* (tests/io/test_instrument_csv.cpp) reads each to the samples of plain.csv.

Run from anywhere: /usr/bin/python3 tests/data/instruments/make_examples.py
The preambles are shortened but keep every line the readers rely on; their other values
(model, serial number, scales) are made up.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLES = 200
STEP_S = 1e-8


def volts(k):
    t = k * STEP_S
    return 0.05 * math.sin(2 * math.pi * 1.25e6 * t) + 0.02 * math.sin(2 * math.pi * 3.1e6 * t + 0.3)


# Every file writes these voltage texts (PicoScope's in mV): the same samples to the digit.
V = ["%.6e" % volts(k) for k in range(SAMPLES)]


def write(name, lines):
    with open(os.path.join(HERE, name), "w", encoding="utf-8", newline="") as f:
        f.write("".join(lines))


write("plain.csv", ["t,V\n"] + ["%r,%s\n" % (k * STEP_S, V[k]) for k in range(SAMPLES)])

# Tektronix TDS1000/TDS2000 "Save All" CSV: preamble in columns 1-2, samples in 4-5, CRLF.
preamble = [("Record Length", "2.000000e+02"), ("Sample Interval", "1.000000e-08"), ("Trigger Point", "0.000000000000"),
            ("", ""), ("", ""), ("", ""), ("Source", "CH1"), ("Vertical Units", "V"), ("Vertical Scale", "2.000000e-02"),
            ("Vertical Offset", "0.000000e+00"), ("Horizontal Units", "s"), ("Horizontal Scale", "2.500000e-07"),
            ("Pt Fmt", "Y"), ("Yzero", "0.000000e+00"), ("Probe Atten", "1.000000e+00"), ("Model Number", "TDS2012B"),
            ("Serial Number", "C000000"), ("Firmware Version", "FV:v22.11")]
rows = preamble + [("", "")] * (SAMPLES - len(preamble))
write("tektronix_tds.csv", ["%s,%s,,%.12f,%s,\r\n" % (*rows[k], k * STEP_S, V[k]) for k in range(SAMPLES)])

# Tektronix MSO/MDO/DPO: key,value preamble, then TIME,CH1.
write("tektronix_mso.csv", ["Model,MDO3024\n", "Firmware Version,1.26\n", "\n", "Waveform Type,ANALOG\n", "Point Format,Y\n",
                            "Horizontal Units,s\n", "Horizontal Scale,2.5e-07\n", "Horizontal Delay,0\n",
                            "Sample Interval,1e-08\n", "Record Length,200\n", "Gating,0.0% to 100.0%\n",
                            "Probe Attenuation,1\n", "Vertical Units,V\n", "Vertical Offset,0\n", "Vertical Scale,0.02\n",
                            "Vertical Position,0\n", ",\n", ",\n", ",\n", "Label,\n", "TIME,CH1\n"]
      + ["%.6e,%s\n" % (k * STEP_S, V[k]) for k in range(SAMPLES)])

# Keysight InfiniiVision: channel numbers, then units, then the samples (two channels here;
# the reader takes the first unless --column names another).
write("keysight.csv", ["x-axis,1,2\n", "second,Volt,Volt\n"]
      + ["%.7E,%s,%s\n" % (k * STEP_S, V[k], "0.0") for k in range(SAMPLES)])

# Rigol DS1000Z: no time column; start and increment in the second line.
write("rigol.csv", ["X,CH1,Start,Increment,\n", "Sequence,VOLT,0.000000e+00,1.000000e-08\n"]
      + ["%d,%s,\n" % (k, V[k]) for k in range(SAMPLES)])

# Teledyne LeCroy spreadsheet export.
write("lecroy.csv", ["LECROYWS3024,11111,Waveform\n", "Segments,1,SegmentSize,200\n", "Segment,TrigTime,TimeSinceSegment1\n",
                     "#1,01-Jan-2024 12:00:00,0                 \n", "Time,Ampl\n"]
      + ["%.6e,%s\n" % (k * STEP_S, V[k]) for k in range(SAMPLES)])

# PicoScope 6: comma-separated in us and mV, and the tab-delimited variant in us and V.
write("picoscope.csv", ["Time,Channel A\n", "(\u00b5s),(mV)\n", "\n"]
      + ["%.8f,%.6e\n" % (k * STEP_S * 1e6, float(V[k]) * 1e3) for k in range(SAMPLES)])
write("picoscope_tab.txt", ["Time\tChannel A\n", "(us)\t(V)\n", "\n"]
      + ["%.8f\t%s\n" % (k * STEP_S * 1e6, V[k]) for k in range(SAMPLES)])
