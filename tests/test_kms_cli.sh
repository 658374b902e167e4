#!/bin/sh
# The KMS display's command-line and scene errors on a machine without the
# device in question (runs anywhere; the VM test vm_kms covers the real path):
#   test_kms_cli.sh FIXTERRAIN OUT_DIR
set -u
fx=$1; out=$2
mkdir -p "$out"
fails=0
expect() { # expect RC TEXT ARGS...: fixterrain exits RC and says TEXT
  rc_want=$1; text=$2; shift 2
  "$fx" "$@" > "$out/kms-cli.log" 2>&1; rc=$?
  if [ "$rc" -ne "$rc_want" ] || ! grep -q -- "$text" "$out/kms-cli.log"; then
    echo "FAIL: fixterrain $*: exit $rc (want $rc_want), output:"; cat "$out/kms-cli.log"
    echo "(wanted: $text)"
    fails=$((fails + 1))
  else
    echo "ok: fixterrain $*: $(grep -m 1 -- "$text" "$out/kms-cli.log")"
  fi
}
# a card that does not exist: a clear error, nothing rendered
expect 1 "KMS: cannot open /dev/dri/card15: No such file or directory" \
  render --display kms:/dev/dri/card15 --size 64x48 --out "$out/kms.png"
# no card named and none with outputs here (when this machine has none)
if ! ls /dev/dri/card* > /dev/null 2>&1; then
  expect 1 "KMS: no DRM card with display outputs" render --display kms --size 64x48 \
    --out "$out/kms.png"
fi
expect 2 "unknown display 'kms:card0'" render --display kms:card0 --out "$out/kms.png"
expect 2 "unknown display 'gbm'" render --display gbm --out "$out/kms.png"
expect 1 "display 'kms' needs an EGL backend" render --display kms --backend osmesa \
  --out "$out/kms.png"
printf '[scene]\ndisplay = kms\n[display]\nmode = 1024by768\n' > "$out/kms-bad.ini"
expect 1 "kms-bad.ini:4: display.mode = '1024by768': expected WxH, WxH@HZ or preferred" \
  render --scene "$out/kms-bad.ini" --out "$out/kms.png"
"$fx" render --help | grep -q "kms\[:/dev/dri/cardN\]" || { echo "FAIL: render --help"; fails=$((fails + 1)); }
[ ! -e "$out/kms.png" ] || { echo "FAIL: a failed KMS open wrote a PNG"; fails=$((fails + 1)); }
[ "$fails" -eq 0 ] || { echo "test_kms_cli: $fails failure(s)"; exit 1; }
echo "test_kms_cli: all checks passed"
