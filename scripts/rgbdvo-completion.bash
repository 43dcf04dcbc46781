# Bash completion for rgbdvo: subcommands; each subcommand's flags as its --help lists them (so
# they never fall behind the program); calibration names after --calib; files elsewhere.
_rgbdvo() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD - 1]}
  local exe=${COMP_WORDS[0]} sub="" i
  for ((i = 1; i < COMP_CWORD; i++)); do
    if [[ ${COMP_WORDS[i]} != -* ]]; then
      sub=${COMP_WORDS[i]}
      break
    fi
  done
  COMPREPLY=()
  if [[ -z $sub ]]; then
    local words="--help --version"
    [[ $cur != -* ]] && words=$("$exe" --help 2>/dev/null | awk '/^Subcommands:/ {f = 1; next} f && NF {print $1}')
    mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
  elif [[ $prev == --calib ]]; then
    mapfile -t COMPREPLY < <(compgen -W "$("$exe" calibrations 2>/dev/null | cut -f1)" -- "$cur"; compgen -f -- "$cur")
  elif [[ $cur == -* ]]; then
    mapfile -t COMPREPLY < <(compgen -W "$("$exe" "$sub" --help 2>/dev/null | grep -oE -- '--[A-Za-z0-9][A-Za-z0-9-]*' | sort -u)" -- "$cur")
  else
    mapfile -t COMPREPLY < <(compgen -f -- "$cur")
  fi
}
complete -o filenames -o bashdefault -F _rgbdvo rgbdvo
