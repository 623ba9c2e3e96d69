#!/usr/bin/env python3
"""plot_scaling.py - the cost-growth plot of docs/performance.md.

Reads the machine lines of `bench --scaling` (its standard error) and
writes an SVG: milliseconds per stage against strands (left) and against
guides (right), log-log, one thread solid, two threads dashed.

    build/bench --scaling 2> scaling.txt
    python3 bench/plot_scaling.py scaling.txt docs/images/scaling.svg
"""
import math
import sys

STAGES = [("roots", "#8c564b"), ("ropes", "#d62728"),
          ("strands_ms", "#1f77b4"), ("ribbons", "#2ca02c"),
          ("points", "#9467bd")]


def read(path):
    rows = []
    with open(path) as f:
        for line in f:
            if not line.startswith("bench stage=scaling "):
                continue
            kv = dict(w.split("=", 1) for w in line.split()[1:])
            rows.append(kv)
    if not rows:
        sys.exit("plot_scaling: no 'bench stage=scaling' lines in " + path)
    return rows


def panel(rows, vary, x0, title):
    w, h, left, top = 420.0, 300.0, x0 + 55.0, 40.0
    sel = [r for r in rows if r["vary"] == vary]
    xs = [float(r["strands" if vary == "strands" else "guides"]) for r in sel]
    ys = [float(r[s]) for r in sel for s, _ in STAGES if float(r[s]) > 0]
    lx0, lx1 = math.log10(min(xs)), math.log10(max(xs))
    ly0, ly1 = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))

    def px(x):
        return left + (math.log10(x) - lx0) / (lx1 - lx0) * w

    def py(y):
        return top + h - (math.log10(y) - ly0) / (ly1 - ly0) * h

    out = ['<text x="%g" y="24" font-size="14">%s</text>' % (left, title)]
    out.append('<rect x="%g" y="%g" width="%g" height="%g" fill="none" '
               'stroke="#999"/>' % (left, top, w, h))
    for e in range(int(ly0), int(ly1) + 1):
        y = py(10.0 ** e)
        out.append('<line x1="%g" y1="%g" x2="%g" y2="%g" stroke="#eee"/>'
                   % (left, y, left + w, y))
        out.append('<text x="%g" y="%g" font-size="11" text-anchor="end">'
                   '%g ms</text>' % (left - 4, y + 4, 10.0 ** e))
    for x in sorted(set(xs)):
        out.append('<text x="%g" y="%g" font-size="11" text-anchor="middle">'
                   '%d</text>' % (px(x), top + h + 16, x))
    out.append('<text x="%g" y="%g" font-size="12" text-anchor="middle">%s'
               '</text>' % (left + w / 2, top + h + 34, vary))
    for stage, color in STAGES:
        for th, dash in (("1", ""), ("2", ' stroke-dasharray="5,4"')):
            pts = sorted((float(r["strands" if vary == "strands" else
                                  "guides"]), float(r[stage]))
                         for r in sel if r["threads"] == th)
            pts = [(x, y) for x, y in pts if y > 0]
            if len(pts) < 2:
                continue
            d = " ".join("%g,%g" % (px(x), py(y)) for x, y in pts)
            out.append('<polyline points="%s" fill="none" stroke="%s" '
                       'stroke-width="2"%s/>' % (d, color, dash))
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scaling.py SCALING_LINES OUT.svg")
    rows = read(sys.argv[1])
    body = panel(rows, "strands", 0, "ms per stage vs strands (1,002 guides)")
    body += panel(rows, "guides", 500, "ms per stage vs guides (100,000 strands)")
    legend = []
    for i, (stage, color) in enumerate(STAGES):
        x = 60 + i * 120
        legend.append('<line x1="%d" y1="400" x2="%d" y2="400" stroke="%s" '
                      'stroke-width="3"/><text x="%d" y="404" '
                      'font-size="12">%s</text>'
                      % (x, x + 24, color, x + 30,
                         stage.replace("_ms", "")))
    legend.append('<text x="680" y="404" font-size="12">solid: 1 thread, '
                  'dashed: 2</text>')
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="1000" '
           'height="420" font-family="sans-serif">',
           '<rect width="1000" height="420" fill="white"/>'] + body + \
        legend + ['</svg>']
    with open(sys.argv[2], "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
