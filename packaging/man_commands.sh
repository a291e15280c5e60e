#!/bin/sh
# Writes the COMMANDS section of clpc's manual page (a help2man include) from the help of
# each subcommand, so the page says what `clpc SUBCOMMAND --help` says.
#   man_commands.sh CLPC > commands.h2m
set -eu
clpc=$1
echo "[COMMANDS]"
"$clpc" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF {print $1}' | while read -r sub; do
  echo ".SS $sub"
  echo ".nf"
  # roff: a backslash is \e; a line starting with . or ' is taken literally after \&
  "$clpc" "$sub" --help | sed -e 's/\\/\\e/g' -e "s/^\([.']\)/\\\\\&\1/" -e 's/^Usage: [^ ]*clpc/Usage: clpc/'
  echo ".fi"
done
