#!/usr/bin/env python3
"""Writes N fields as GeoJSON in longitude/latitude (each a quadrilateral about 100 m across with a
building hole), for timing `coverbench dataset import` (docs/performance.md).
    python3 bench/import/fields_geojson.py N OUT.geojson"""
import json
import random
import sys


def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    rng = random.Random(7)
    features = []
    for i in range(n):
        lon, lat = 8.0 + (i % 100) * 0.002, 47.0 + (i // 100) * 0.002
        w, h = rng.uniform(0.0008, 0.0013), rng.uniform(0.0006, 0.0009)  # about 60-100 m by 65-100 m
        outer = [[lon, lat], [lon + w, lat + 0.00005], [lon + w, lat + h], [lon, lat + h], [lon, lat]]
        hx, hy = lon + w * 0.4, lat + h * 0.4
        hole = [[hx, hy], [hx, hy + 0.0001], [hx + 0.00015, hy + 0.0001], [hx + 0.00015, hy], [hx, hy]]
        features.append({"type": "Feature", "properties": {"name": "field_%05d" % i},
                         "geometry": {"type": "Polygon", "coordinates": [outer, hole]}})
    with open(out, "w") as f:
        json.dump({"type": "FeatureCollection", "features": features}, f)


if __name__ == "__main__":
    main()
