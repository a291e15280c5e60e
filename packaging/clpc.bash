# bash completion for clpc: subcommands, each one's options (read from its --help, so they
# never drift), machine names from `clpc machines` after -t and for explain, choices of
# --emit, --input-units and --input-encoding, and files elsewhere.
_clpc() {
  local cur prev
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD-1]}
  local clpc=${COMP_WORDS[0]}
  if ((COMP_CWORD == 1)); then
    local subs
    subs=$("$clpc" --help 2>/dev/null | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF {print $1}')
    COMPREPLY=($(compgen -W "$subs --help --version" -- "$cur"))
    return
  fi
  local sub=${COMP_WORDS[1]}
  case $prev in
    -t|--target)
      COMPREPLY=($(compgen -W "$("$clpc" machines 2>/dev/null | cut -f1)" -- "$cur") $(compgen -f -X '!*.toml' -- "$cur"))
      return ;;
    --machines|--job)
      COMPREPLY=($(compgen -f -X '!*.toml' -- "$cur") $(compgen -d -- "$cur"))
      return ;;
    --output-dir)
      COMPREPLY=($(compgen -d -- "$cur"))
      return ;;
    --emit) COMPREPLY=($(compgen -W "gcode ir" -- "$cur")); return ;;
    --input-units) COMPREPLY=($(compgen -W "mm inch" -- "$cur")); return ;;
    --input-encoding) COMPREPLY=($(compgen -W "utf-8 latin1" -- "$cur")); return ;;
    -o|--output|--program|--report|--set|--tolerance|--axis-tolerance|-j|--jobs|--width|--height|--print-after)
      COMPREPLY=($(compgen -f -- "$cur"))
      return ;;
  esac
  if [[ $cur == -* ]]; then
    local opts
    opts=$("$clpc" "$sub" --help 2>/dev/null | grep -oE '(^|[ ,])--?[A-Za-z][A-Za-z0-9-]*' | tr -d ' ,' | sort -u)
    COMPREPLY=($(compgen -W "$opts" -- "$cur"))
  elif [[ $sub == explain ]]; then
    COMPREPLY=($(compgen -W "$("$clpc" machines 2>/dev/null | cut -f1)" -- "$cur") $(compgen -f -X '!*.toml' -- "$cur"))
  else
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}
complete -o filenames -F _clpc clpc
