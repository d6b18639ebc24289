#!/usr/bin/env bash
# Seeds for fuzz_http_api: one request per file, as a client would send it (the fuzzer's token
# is fuzz/fuzz_http_api.cpp's kToken). Usage: fuzz/http_seeds.sh CORPUS_DIR
set -euo pipefail
out="$1"
mkdir -p "$out"
auth='Authorization: Bearer fuzz-token-0123456789abcdef'
n=0
seed() {
  n=$((n + 1))
  printf '%b' "$1" >"$out/seed-$n.http"
}
post() {  # target body
  seed "POST $1 HTTP/1.1\r\nHost: 127.0.0.1:8470\r\n$auth\r\nContent-Type: application/json\r\nContent-Length: ${#2}\r\n\r\n$2"
}
for target in /api/status /api/live?since=0\&limit=10 /api/runs /api/runs?procedure=static\&status=complete\&unit=SN-1\&limit=5 \
  /api/runs/20261122T045843.123456Z /api/runs/20261122T045843.123456Z/samples?from=0\&limit=100; do
  seed "GET $target HTTP/1.1\r\nHost: 127.0.0.1:8470\r\n\r\n"
done
seed "GET /api/status HTTP/1.1\r\nHost: localhost:8470\r\nConnection: close\r\n\r\n"
post /api/runs '{"procedure":"static","options":{"positions":4,"loads_nm":[0,60]},"twin":false}'
post /api/runs '{"procedure":"dynamic","options":{"output_revolutions":2,"input_rpm":100}}'
post /api/runs '{"procedure":"lost-motion","options":{},"report":true}'
post /api/runs '{"procedure":"static","options":{"limits":{"static_te_p2p_arcmin":{"max":6}}}}'
post /api/abort '{}'
post /api/stop '{}'
post /api/reset '{}'
