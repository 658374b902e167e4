# Sourced by the CLI test scripts: fail counts a failure; expect runs a
# command and checks its exit status and output.
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# expect CODE NEEDLE -- CMD...: exit status CODE and NEEDLE in stdout+stderr
expect() {
  code=$1; needle=$2; shift 3
  text=$("$@" 2>&1); rc=$?
  [ "$rc" -eq "$code" ] || fail "'$*' exited $rc, expected $code: $text"
  case "$text" in *"$needle"*) ;; *) fail "'$*' output lacks '$needle': $text" ;; esac
}
