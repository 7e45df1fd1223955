"""Line plots as SVG files without a plotting library, for the examples' plot.py scripts
(each imports it from the folder above its own)."""

COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]


def svg(path, title, xlabel, ylabel, series, equal=False, size=(640, 480)):
    """Writes `series`, a list of (name, xs, ys), as lines in one frame to `path`. With `equal`,
    both axes get the same scale (an orbit keeps its shape)."""
    xs = [x for _, x, _ in series for x in x]
    ys = [y for _, _, y in series for y in y]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    if equal:
        c, s = ((x0 + x1) / 2, (y0 + y1) / 2), max(x1 - x0, y1 - y0) / 2 or 1e-9
        x0, x1, y0, y1 = c[0] - s, c[0] + s, c[1] - s, c[1] + s
    x1, y1 = (x1 if x1 > x0 else x0 + 1), (y1 if y1 > y0 else y0 + 1)
    (W, H), m = size, 60
    X = lambda x: m + (x - x0) / (x1 - x0) * (W - 2 * m)
    Y = lambda y: H - m - (y - y0) / (y1 - y0) * (H - 2 * m)
    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/><rect x="{m}" y="{m}" width="{W-2*m}" height="{H-2*m}" fill="none" stroke="black"/>',
         f'<text x="{W/2}" y="25" text-anchor="middle" font-size="14">{title}</text>',
         f'<text x="{W/2}" y="{H-15}" text-anchor="middle">{xlabel}</text>',
         f'<text x="15" y="{H/2}" transform="rotate(-90 15 {H/2})" text-anchor="middle">{ylabel}</text>']
    for v, f in ((x0, 0), (x1, 0), (y0, 1), (y1, 1)):
        o.append(f'<text x="{X(v) if f == 0 else m - 5}" y="{H - m + 15 if f == 0 else Y(v)}" '
                 f'text-anchor="{"middle" if f == 0 else "end"}">{v:.4g}</text>')
    for k, (name, x, y) in enumerate(series):
        pts = " ".join(f"{X(a):.1f},{Y(b):.1f}" for a, b in zip(x, y))
        o.append(f'<polyline points="{pts}" fill="none" stroke="{COLORS[k % 4]}" stroke-width="1"/>')
        o.append(f'<text x="{W - m - 5}" y="{m + 15 + 15 * k}" text-anchor="end" fill="{COLORS[k % 4]}">{name}</text>')
    open(path, "w").write("\n".join(o) + "\n</svg>\n")
