"""The one HTML page generator: experiment reports and the showcase share its layout, table of
contents, tables and side-by-side galleries. Everything from data is escaped."""
import html

# The sections are laid out only as they come near the screen (content-visibility), so a large
# report's first screen is drawn, and its load event comes, before its long tables are laid out.
STYLE = """
body{font-family:system-ui,sans-serif;margin:0;color:#222;background:#fff}
header{padding:1em 2em;background:#f4f1ea;border-bottom:1px solid #ddd}
nav{position:sticky;top:0;background:#fff;border-bottom:1px solid #ddd;padding:.4em 2em;z-index:2;font-size:14px}
nav a{margin-right:1.2em}
main{padding:0 2em 3em}
h2{border-bottom:2px solid #ccc;padding-top:.6em}
table{border-collapse:collapse;font-size:13px;margin:.5em 0}
caption{text-align:left;font-weight:600;padding:.3em 0}
th,td{border:1px solid #ddd;padding:2px 7px;text-align:right;white-space:nowrap}
th[scope=row],td:first-child,td.text{text-align:left}
thead th{background:#f6f6f6}
.table-wrap{overflow-x:auto}
.note{font-size:12px;color:#555;max-width:110ch}
img.figure{max-width:100%;border:1px solid #eee;margin:.4em 0}
.gallery{display:grid;grid-template-columns:repeat(auto-fill,minmax(380px,1fr));gap:10px}
.gallery figure{margin:0;border:1px solid #ddd;padding:4px;background:#fafafa}
.gallery img{width:100%;height:auto}
img.figure{height:auto}
.gallery figcaption{font-size:12px}
.status-bad{color:#b00020;font-weight:600}
pre{background:#f6f6f6;padding:.6em;overflow-x:auto;font-size:12px}
main>section{content-visibility:auto;contain-intrinsic-size:auto 1500px}
"""


def esc(text):
    return html.escape(str(text), quote=True)


def size_attributes(width, height):
    """' width="W" height="H"' of an image (the page keeps its room before it loads), or nothing."""
    return f' width="{int(width)}" height="{int(height)}"' if width and height else ""


def figure(src, alt, size=None):
    """A figure, loaded when scrolled near (`size`: its (width, height) in pixels, if known)."""
    return (f'<p><a href="{esc(src)}"><img class="figure" src="{esc(src)}" alt="{esc(alt)}" loading="lazy" '
            f'decoding="async"{size_attributes(*(size or (0, 0)))}></a></p>')


# A wall whose runs have coat pictures (a tool with a flux profile) shows each run's path and coat
# side by side in one cell of the gallery, its cells twice as wide. Set on the elements, so the
# pages of other experiments stay as they were.
COAT_GALLERY = "grid-template-columns:repeat(auto-fill,minmax(760px,1fr))"
COAT_PAIR = "display:grid;grid-template-columns:1fr 1fr;gap:6px;align-items:start"


def gallery_html(section):
    """Walls of one gallery section, each with every planner's picture side by side (and its
    coat's beside it, for a tool with a flux profile)."""
    out = []
    for wall in section["walls"]:
        out.append(f"<h4>{esc(wall['wall_name'])} <small>({esc(wall['why'])})</small></h4>")
        coats = any(p.get("coat") for p in wall["pictures"])
        out.append(f'<div class="gallery" style="{COAT_GALLERY}">' if coats else '<div class="gallery">')
        for p in wall["pictures"]:
            bad = p["status"] not in ("ok",)
            play = f' data-playback="{esc(p["playback"])}"' if p.get("playback") else ""
            alt = wall["wall_name"] + " / " + p["column"]
            # Loaded when scrolled near, its room kept meanwhile: the first screen does not wait
            # for the hundreds of pictures below it.
            picture = (f'<figure{play}><a href="{esc(p["file"])}"><img src="{esc(p["file"])}" '
                       f'alt="{esc(alt)}" loading="lazy" decoding="async"'
                       f'{size_attributes(p.get("width"), p.get("height"))}></a>'
                       f'<figcaption>{esc(p["column"])}: <span class="{"status-bad" if bad else ""}">'
                       f'{esc(p["status"])}</span>'
                       + (f'<br><small>{esc(p["note"])}</small>' if p.get("note") else "") + "</figcaption></figure>")
            if not coats:
                out.append(picture)
                continue
            coat = (f'<figure class="coat"><a href="{esc(p["coat"])}"><img src="{esc(p["coat"])}" '
                    f'alt="{esc(alt + ": the coat")}" loading="lazy" decoding="async"'
                    f'{size_attributes(p.get("coat_width"), p.get("coat_height"))}></a>'
                    f'<figcaption>{esc(p["column"])}: the coat\'s thickness (\u00b5m)</figcaption></figure>'
                    if p.get("coat") else "")
            out.append(f'<div class="coat-pair" style="{COAT_PAIR}">{picture}{coat}</div>')
        out.append("</div>")
    return "\n".join(out)


def page(title, subtitle_html, sections, scripts=()):
    """sections: (anchor, heading, body html) in order; the table of contents lists them.
    scripts: our own script files beside the page (never data), loaded at its end."""
    nav = " ".join(f'<a href="#{esc(a)}">{esc(h)}</a>' for a, h, _ in sections)
    body = "\n".join(f'<section id="{esc(a)}"><h2>{esc(h)}</h2>\n{b}\n</section>' for a, h, b in sections)
    return (f'<!doctype html>\n<html lang="en"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{esc(title)}</title><style>{STYLE}</style></head><body>\n"
            f"<header><h1>{esc(title)}</h1>{subtitle_html}</header>\n<nav>{nav}</nav>\n<main>\n{body}\n</main>\n"
            + "".join(f'<script src="{esc(s)}"></script>\n' for s in scripts)
            + "</body></html>\n")
