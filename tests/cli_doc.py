#!/usr/bin/python3
"""docs/cli.md against the command line: usage `cli_doc.py IRAD DOC`.

For every subcommand that `IRAD --help` lists, the long options that `IRAD SUB --help` prints
(`--help` aside; hidden options are not printed) must equal the long options named in the first
column of the tables under the doc's heading `## irad SUB` (down to the next heading of level 1
or 2), and the doc must have no section for a subcommand the CLI lacks. On a difference it prints
one line per subcommand naming the options missing on each side and exits 1. Standard library
only.
"""
import re
import subprocess
import sys

LONG = re.compile(r"--[A-Za-z0-9][A-Za-z0-9-]*")
# CLI11's help: an option's names start at column 2 ("  -o,--output TEXT ..."); a description
# too long for its line continues indented by the name column's width, never at column 2.
HELP_OPTION = re.compile(r"^  (?:-[A-Za-z0-9],\s*)?(--[A-Za-z0-9][A-Za-z0-9-]*)")
SECTION = re.compile(r"^##\s+`?irad\s+([a-z][a-z0-9-]*)")


def run_help(irad, args):
    p = subprocess.run([irad, *args, "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=30)
    if p.returncode != 0:
        sys.exit(f"cli_doc: `{' '.join([irad, *args, '--help'])}` exited with {p.returncode}:\n"
                 f"{p.stdout}")
    return p.stdout


def subcommands(irad):
    names, inside = [], False
    for line in run_help(irad, []).splitlines():
        if re.match(r"^Subcommands:", line):
            inside = True
        elif inside and re.match(r"^  [a-z]", line):
            names.append(line.split()[0])
        elif inside and line.strip() and not line.startswith(" "):
            inside = False
    if not names:
        sys.exit("cli_doc: `irad --help` lists no subcommands")
    return names


def help_options(irad, sub):
    found = set()
    for line in run_help(irad, [sub]).splitlines():
        m = HELP_OPTION.match(line)
        if m:
            found.add(m.group(1))
    found.discard("--help")
    return found


def doc_options(path):
    """{subcommand: set of long options in the first cell of its table's rows}."""
    sections, current, fence = {}, None, False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                fence = not fence
                continue
            if fence:
                continue
            m = SECTION.match(line)
            if m:
                current = m.group(1)
                if current in sections:
                    sys.exit(f"cli_doc: {path}: two sections for `irad {current}`")
                sections[current] = set()
                continue
            if re.match(r"^#{1,2}\s", line):
                current = None  # a heading of level 1 or 2 ends the section; ### stay in it
                continue
            if current is None or not line.lstrip().startswith("|"):
                continue
            cells = line.strip().strip("|").split("|")
            first = cells[0].strip()
            if first == "option" or set(first) <= set("-: "):
                continue  # the header row and the separator
            sections[current].update(LONG.findall(first.replace("\\|", "|")))
    for s in sections.values():
        s.discard("--help")
    return sections


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: cli_doc.py IRAD docs/cli.md")
    irad, doc = sys.argv[1], sys.argv[2]
    documented = doc_options(doc)
    problems = []
    subs = subcommands(irad)
    for sub in subs:
        cli = help_options(irad, sub)
        if sub not in documented:
            problems.append(f"{sub}: no section `## irad {sub}` in {doc} "
                            f"(the CLI has {', '.join(sorted(cli))})")
            continue
        not_in_doc = sorted(cli - documented[sub])
        not_in_cli = sorted(documented[sub] - cli)
        if not_in_doc or not_in_cli:
            problems.append(
                f"{sub}: in `irad {sub} --help` but not in {doc}: {', '.join(not_in_doc) or '-'}; "
                f"in {doc} but not in `irad {sub} --help`: {', '.join(not_in_cli) or '-'}")
    for sub in sorted(set(documented) - set(subs)):
        problems.append(f"{sub}: {doc} has a section `## irad {sub}`, but irad has no such "
                        "subcommand")
    if problems:
        print("cli_doc: docs/cli.md and the CLI differ:", file=sys.stderr)
        for p in problems:
            print("  " + p, file=sys.stderr)
        return 1
    print(f"cli_doc: {len(subs)} subcommands, {sum(len(documented[s]) for s in subs)} options: "
          "docs and --help agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
