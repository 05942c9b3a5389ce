#!/usr/bin/env python3
"""The man page and the bash completion of stengmc, made from its own --help.

    make_cli_docs.py STENGMC_BINARY MAN_PAGE_OUT COMPLETION_OUT

The command line is defined once, in the CLI11 code of src/app/; its --help is what a user
reads, so the man page (stengmc(1), every command's help verbatim under COMMANDS) and the
completion (commands, then each command's options, file names where a value is expected)
are derived from that text at build time and cannot drift from it. Installed by
`cmake --install` (share/man/man1/stengmc.1, share/bash-completion/completions/stengmc).
"""
import re
import subprocess
import sys

SECTION = re.compile(r"^(Positionals|Options|Subcommands):\s*$")
OPTION = re.compile(r"^  (-[^\s]+(?:,-[^\s]+)*)(?: ([A-Z][A-Z0-9_/]+)(?=[:\s]|$))?")  # one space, then the value's type
SUBCOMMAND = re.compile(r"^  ([a-z][a-z0-9-]*)\s{2,}")


def help_text(binary, *args):
    out = subprocess.run([binary, *args, "--help"], check=True, capture_output=True, text=True).stdout
    # The usage line names the binary as it was called (./build/src/stengmc): a reader's is `stengmc`.
    return re.sub(r"^Usage: \S+", "Usage: stengmc", out, flags=re.M)


def sections(text):
    """{section name: [lines]} of a CLI11 help text."""
    found, current = {}, None
    for line in text.splitlines():
        m = SECTION.match(line)
        if m:
            current = m.group(1)
            found[current] = []
        elif current:
            found[current].append(line)
    return found


def subcommands(top_help):
    return [m.group(1) for line in sections(top_help).get("Subcommands", []) if (m := SUBCOMMAND.match(line))]


def options(command_help):
    """[(names, takes_value)] of a command's options."""
    out = []
    for line in sections(command_help).get("Options", []):
        m = OPTION.match(line)
        if m:
            out.append((m.group(1).split(","), bool(m.group(2))))
    return out


def roff(text):
    """Text as roff shows it verbatim: backslashes doubled, a leading dot or quote escaped."""
    lines = []
    for line in text.replace("\\", "\\e").splitlines():
        lines.append("\\&" + line if line.startswith((".", "'")) else line)
    return "\n".join(lines)


def man_page(binary, version, commands):
    top = help_text(binary)
    parts = [f'.TH STENGMC 1 "" "stengmc {version}" "User Commands"',
             ".SH NAME", "stengmc \\- Monte Carlo studies of sliding triboelectric sensors on rough surfaces",
             ".SH SYNOPSIS", "\\fBstengmc\\fR \\fICOMMAND\\fR [\\fIOPTIONS\\fR] ...",
             ".SH DESCRIPTION", ".nf", roff(top), ".fi", ".SH COMMANDS"]
    for command in commands:
        parts += [f".SS {command}", ".nf", roff(help_text(binary, command)), ".fi"]
    parts += [".SH FILES", "Study and surface files: TOML, described in share/doc/stengmc/study-files.md; "
              "outputs: HDF5 (netCDF-4), described in share/doc/stengmc/output-files.md.",
              ".SH EXIT STATUS", "0 done; 2 bad input; 3 the model is outside its validity; 1 anything else; "
              "130/143 stopped by SIGINT/SIGTERM (an ensemble resumes from its journal).",
              ".SH SEE ALSO", "share/doc/stengmc/README.md, model.md, inverse.md"]
    return "\n".join(parts) + "\n"


def completion(binary, commands):
    cases = []
    for command in commands:
        opts = options(help_text(binary, command))
        words = " ".join(name for names, _ in opts for name in names)
        valued = "|".join(name for names, takes in opts if takes for name in names) or "--no-such-option"
        cases.append(f'    {command})\n      opts="{words}"\n      valued="{valued}" ;;')
    return f"""# bash completion for stengmc, made from its --help by scripts/make_cli_docs.py
_stengmc() {{
  local cur prev command opts valued
  cur="${{COMP_WORDS[COMP_CWORD]}}"
  prev="${{COMP_WORDS[COMP_CWORD-1]}}"
  command="${{COMP_WORDS[1]}}"
  if [[ $COMP_CWORD -eq 1 ]]; then
    COMPREPLY=($(compgen -W "{' '.join(commands)} --help --version" -- "$cur"))
    return
  fi
  case "$command" in
{chr(10).join(cases)}
    *) return ;;
  esac
  if [[ "$prev" == @($valued) ]]; then
    COMPREPLY=($(compgen -f -- "$cur"))
  elif [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$opts" -- "$cur"))
  else
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}}
complete -o filenames -F _stengmc stengmc
"""


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    binary, man_out, completion_out = argv
    version = subprocess.run([binary, "--version"], check=True, capture_output=True, text=True).stdout.split()[1]
    commands = subcommands(help_text(binary))
    if not commands:
        sys.exit(f"{binary} --help lists no subcommands: cannot make the man page")
    with open(man_out, "w") as f:
        f.write(man_page(binary, version, commands))
    with open(completion_out, "w") as f:
        f.write(completion(binary, commands))


if __name__ == "__main__":
    main(sys.argv[1:])
