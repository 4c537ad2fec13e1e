#!/usr/bin/env python3
"""Medians (and range) per configuration of the CSV that measure_vpl_throughput.sh writes."""
import collections
import csv
import statistics
import sys

rows = collections.defaultdict(list)
for row in csv.DictReader(open(sys.argv[1])):
    rows[row["config"]].append(float(row["vpls_per_second"]))
print("config,runs,median,min,max")
for config, values in rows.items():
    print(f"{config},{len(values)},{statistics.median(values):.0f},{min(values):.0f},{max(values):.0f}")
