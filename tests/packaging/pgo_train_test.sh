#!/usr/bin/env bash
# scripts/pgo-train, the profile-guided build's training run and its check
# (cmake/profile_guided.cmake), with the release dpscope standing in for both builds: the check
# passes for the same binary, and fails for one whose captures, output, messages or exit code
# differ; a run that dies on a signal, ends in a usage error or writes nothing fails the training.
# Usage: pgo_train_test.sh PGO_TRAIN DPSCOPE
set -uo pipefail
train=${1:?usage: pgo_train_test.sh PGO_TRAIN DPSCOPE}
dpscope=$(realpath "${2:?usage: pgo_train_test.sh PGO_TRAIN DPSCOPE}")
tmp=$(mktemp -d "${TMPDIR:-/tmp}/dpscope-pgo.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
status=0
fail() {
    echo "FAILED: $*" >&2
    status=1
}

# Usage errors: exit 2.
"$train" >/dev/null 2>&1
[[ $? == 2 ]] || fail "no arguments: not exit 2"
"$train" learn "$dpscope" "$tmp/x" >/dev/null 2>&1
[[ $? == 2 ]] || fail "an unknown mode: not exit 2"

# Training: a checksum, an exit code and a name a run, and the mark that it is done.
if ! "$train" train "$dpscope" "$tmp/training" >"$tmp/train.out" 2>&1; then
    fail "training with $dpscope: $(cat "$tmp/train.out")"
fi
[[ -f $tmp/training/trained ]] || fail "no 'trained' mark"
runs=$(wc -l <"$tmp/training/outputs.sha256")
[[ $runs -ge 60 ]] || fail "only $runs runs recorded"
grep -Eq '^[0-9a-f]{64} [0-9a-f]{64} 1 profibus\.report$' "$tmp/training/outputs.sha256" ||
    fail "the PROFIBUS report's line (findings: exit code 1) is not recorded"
grep -Eq '^[0-9a-f]{64} [0-9a-f]{64} 0 dpv1\.jsonl$' "$tmp/training/outputs.sha256" ||
    fail "the DP-V1 jsonl line is not recorded"
grep -q ' sample\.faults\.pcap\.report$' "$tmp/training/outputs.sha256" ||
    fail "the samples are not read"

# Nothing to check against without a finished training.
"$train" check "$dpscope" "$tmp/nothing" >/dev/null 2>&1 && fail "a check without a training passes"

# The same binary passes the check.
"$train" check "$dpscope" "$tmp/training" >"$tmp/check.out" 2>&1 ||
    fail "the same binary fails the check: $(cat "$tmp/check.out")"

# after NAME LINE: $tmp/NAME runs dpscope, then LINE (bash; dpscope's arguments are $1...), and
# exits with dpscope's exit code. before NAME LINE: LINE first, then dpscope in its place.
after() {
    printf '#!/usr/bin/env bash\n%q "$@"\ncode=$?\n%s\nexit $code\n' "$dpscope" "$2" >"$tmp/$1"
    chmod +x "$tmp/$1"
}
before() {
    printf '#!/usr/bin/env bash\n%s\nexec %q "$@"\n' "$2" "$dpscope" >"$tmp/$1"
    chmod +x "$tmp/$1"
}
# fails MODE NAME WHAT [SAID]: `pgo-train MODE $tmp/NAME` fails (and its messages hold SAID).
fails() {
    local mode=$1 name=$2 what=$3 said=${4:-} folder=$tmp/training
    [[ $mode == train ]] && folder=$tmp/$name.training
    if "$train" "$mode" "$tmp/$name" "$folder" >"$tmp/$name.out" 2>&1; then
        fail "$what: $mode passes"
    elif [[ -n $said ]] && ! grep -q "$said" "$tmp/$name.out"; then
        fail "$what: $mode does not say '$said': $(cat "$tmp/$name.out")"
    fi
    [[ $mode == train && -f $folder/trained ]] && fail "$what: the failed training is marked done"
}

# The check fails for another output, naming the run; another capture of the simulator, naming
# the session; another message on standard error; another exit code.
after other-output '[[ $1 == report ]] && echo one more line'
fails check other-output "a binary with another report" 'profibus\.report'
after other-capture '[[ $1 == simulate && $4 == -w ]] && echo one more byte >> "$5"'
fails check other-capture "a simulator writing another capture" 'profibus\.simulate'
after other-message '[[ $1 == decode && $2 == -V ]] && echo "dpscope: note: one more" >&2'
fails check other-message "a binary with another message"
after other-code '[[ $1 == stats ]] && exit 4'
fails check other-code "a binary with another exit code"

# The training fails for a run that dies on a signal (its exit code said), that ends in a usage
# error (exit 2; its message shown), or that writes nothing.
before crashing '[[ $1 == decode && $2 == -q ]] && kill -SEGV $$'
fails train crashing "a binary that crashes" 'exit code 139'
before usage-error '[[ $1 == stats ]] && { echo "dpscope: error: no such option" >&2; exit 2; }'
fails train usage-error "a run ending in a usage error" 'no such option'
before silent '[[ $1 == report ]] && exit 0'
fails train silent "a run writing nothing"

[[ $status == 0 ]] && echo "pgo-train: every case as expected"
exit $status
