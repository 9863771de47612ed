#!/usr/bin/env bash
# scripts/pgo-train, the profile-guided build's training run and its check
# (cmake/profile_guided.cmake), with the release dpscope standing in for both builds: the check
# passes for the same binary, and fails for one whose captures, output, messages or exit code
# differ; a run
# that dies on a signal, ends in a usage error or writes nothing fails the training.
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

# A binary whose report writes one more line fails it, naming the runs.
cat >"$tmp/other-output" <<EOF
#!/usr/bin/env bash
"$dpscope" "\$@"
code=\$?
[[ \$1 == report ]] && echo one more line
exit \$code
EOF
chmod +x "$tmp/other-output"
if "$train" check "$tmp/other-output" "$tmp/training" >"$tmp/other.out" 2>&1; then
    fail "a binary with another report passes the check"
elif ! grep -q 'profibus\.report' "$tmp/other.out"; then
    fail "the check does not name the run that differs: $(cat "$tmp/other.out")"
fi

# A binary whose simulator writes another capture fails it (simulate --bus BUS -w FILE ...).
cat >"$tmp/other-capture" <<EOF
#!/usr/bin/env bash
"$dpscope" "\$@"
code=\$?
[[ \$1 == simulate && \$4 == -w ]] && echo one more byte >> "\$5"
exit \$code
EOF
chmod +x "$tmp/other-capture"
if "$train" check "$tmp/other-capture" "$tmp/training" >"$tmp/capture.out" 2>&1; then
    fail "a binary whose simulator writes another capture passes the check"
elif ! grep -q 'profibus\.simulate' "$tmp/capture.out"; then
    fail "the check does not name the session that differs: $(cat "$tmp/capture.out")"
fi

# A binary with another message on standard error fails it.
cat >"$tmp/other-message" <<EOF
#!/usr/bin/env bash
"$dpscope" "\$@"
code=\$?
[[ \$1 == decode && \$2 == -V ]] && echo "dpscope: note: one more" >&2
exit \$code
EOF
chmod +x "$tmp/other-message"
"$train" check "$tmp/other-message" "$tmp/training" >/dev/null 2>&1 &&
    fail "a binary with another message passes the check"

# A binary with another exit code fails it.
cat >"$tmp/other-code" <<EOF
#!/usr/bin/env bash
"$dpscope" "\$@"
code=\$?
[[ \$1 == stats ]] && exit 4
exit \$code
EOF
chmod +x "$tmp/other-code"
"$train" check "$tmp/other-code" "$tmp/training" >/dev/null 2>&1 &&
    fail "a binary with another exit code passes the check"

# A binary that dies on a signal fails training, with the exit code in the message.
cat >"$tmp/crashing" <<EOF
#!/usr/bin/env bash
[[ \$1 == decode && \$2 == -q ]] && kill -SEGV \$\$
exec "$dpscope" "\$@"
EOF
chmod +x "$tmp/crashing"
if "$train" train "$tmp/crashing" "$tmp/crash" >"$tmp/crash.out" 2>&1; then
    fail "a binary that crashes trains"
elif ! grep -q 'exit code 139' "$tmp/crash.out"; then
    fail "the crash's message does not give its exit code: $(cat "$tmp/crash.out")"
fi
[[ -f $tmp/crash/trained ]] && fail "a failed training is marked done"

# A run that ends in a usage error (exit 2), or writes nothing, fails the training.
cat >"$tmp/usage-error" <<EOF
#!/usr/bin/env bash
[[ \$1 == stats ]] && { echo "dpscope: error: no such option" >&2; exit 2; }
exec "$dpscope" "\$@"
EOF
chmod +x "$tmp/usage-error"
if "$train" train "$tmp/usage-error" "$tmp/usage" >"$tmp/usage.out" 2>&1; then
    fail "a run ending in a usage error trains"
elif ! grep -q 'no such option' "$tmp/usage.out"; then
    fail "the usage error's message is not shown: $(cat "$tmp/usage.out")"
fi
cat >"$tmp/silent" <<EOF
#!/usr/bin/env bash
[[ \$1 == report ]] && exit 0
exec "$dpscope" "\$@"
EOF
chmod +x "$tmp/silent"
"$train" train "$tmp/silent" "$tmp/silent-run" >/dev/null 2>&1 && fail "a run writing nothing trains"

[[ $status == 0 ]] && echo "pgo-train: every case as expected"
exit $status
