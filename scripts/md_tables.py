"""Markdown tables for the scripts' summaries."""

import os


def table(header, rows):
    """A Markdown table; rows are sequences of already formatted cells."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def write(path, title, text):
    """Writes `# title`, a blank line and text to path (creating its folder)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(f"# {title}\n\n{text}\n")
