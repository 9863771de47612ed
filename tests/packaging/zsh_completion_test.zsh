# zsh completion (issue 32), as a user gets it: an interactive zsh on a pseudo-terminal (zpty) with
# dpscope's _dpscope in its fpath presses Tab after "dpscope de" (the first Tab, which loads the
# script) and after "dpscope decode -T j". Each read waits for the completed word; a completion
# that never comes is a hang that the caller's time limit ends (completion_test.sh).
# Usage: zsh -f zsh_completion_test.zsh DPSCOPE FOLDER_WITH__dpscope
zmodload zsh/zpty || exit 1
dpscope=$1 folder=$2
zpty -b z "PS1='> ' zsh -f -i"
zpty -w z "PATH=${dpscope:h}:\$PATH; fpath=($folder \$fpath); autoload -U compinit; compinit -u; echo RE''ADY"
zpty -r -m z out '*READY*' || exit 1
zpty -w -n z $'dpscope de\t'
zpty -r -m z out '*dpscope decode*' || exit 1
zpty -w -n z $'\x15dpscope decode -T j\t'
zpty -r -m z out '*-T jsonl*' || exit 1
zpty -d z
print "zsh completion: ok"
