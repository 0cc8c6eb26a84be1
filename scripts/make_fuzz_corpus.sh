#!/usr/bin/env bash
# Builds a fuzzer's seed corpus from the shipped inputs:
#   make_fuzz_corpus.sh DIR [scene|mechanism|study|map_study|journal]   (default scene)
# scene: each scene once without and once with a --set line; mechanism, study,
# map_study: the shipped documents of that kind; journal: a small study journal. Plus
# inputs that once got past the loaders: pointers nlohmann cannot resolve (an empty last
# token, an index beyond 64 bits), a key given twice, bytes after a NUL.
set -euo pipefail
out=${1:?corpus dir}
kind=${2:-scene}
studies="$(dirname "$0")/../studies"
mkdir -p "$out"
i=0
case "$kind" in
  scene)
    for f in "$studies"/scenes/*.json; do
      { echo ""; cat "$f"; } > "$out/scene_$i"
      { echo "/controller/hop_height=0.3"; cat "$f"; } > "$out/set_$i"
      i=$((i + 1))
    done
    scene="$studies/scenes/case1_body_only.json"
    { echo "/controller/kp/99999999999999999999999=1"; cat "$scene"; } > "$out/bad_index"
    { echo '/controller/kp/={"a": 1, "a": 2}'; cat "$scene"; } > "$out/bad_set_value"
    { echo ""; echo '{"name": "a", "name": "b"}'; } > "$out/duplicate_key"
    { echo ""; printf '{"name": "a"}\0{"x": ['; } > "$out/nul_then_bytes" ;;
  mechanism) cp "$studies"/mechanisms/*.json "$out/" ;;
  study)
    cp "$studies"/study*.json "$out/"
    study1="$studies/study1_body_only_gains.json"
    sed 's|"/controller/kp/0"|"/controller/kp/"|' "$study1" > "$out/bad_pointer_empty_token"
    sed 's|"/controller/kp/0"|"/controller/kp/99999999999999999999999"|' "$study1" \
      > "$out/bad_pointer_huge_index" ;;
  map_study)
    cp "$studies"/map_*.json "$out/"
    sed 's|{"kind": "lateral_offset", "range"|{"kind": "pointer", "pointer": "/controller/kp/", "range"|' \
      "$studies/map_study3_full_tilt_offset.json" > "$out/bad_axis_pointer" ;;
  journal)
    # The fuzz target seals each line with its checksum itself (chained: format 2);
    # journal_1 is an older pronk's (format 1, no "format" in the header).
    cat > "$out/journal_0" <<'JOURNAL'
{"constraints":[],"format":2,"optimizer":"nlopt:LN_BOBYQA","parameters":["kp_x","kd_x"],"seed":2,"study":"s","study_hash":"0123456789abcdef","type":"header"}
{"constraints":[0.5],"cost":0.25,"index":0,"metrics":{"y_error":0.1},"ok":true,"purpose":"objective","simulations":4,"spectral_radius":0.5,"strides":40,"type":"evaluation","values":{"kd_x":2.25,"kp_x":1.5},"x":[0.5,0.5]}
{"constraints":[1.0],"cost":1000.0,"failure":"scene: invalid","index":1,"ok":false,"purpose":"gradient","simulations":0,"spectral_radius":10,"strides":0,"type":"evaluation","values":{},"x":[0.25,1.0]}
JOURNAL
    sed '1s/"format":2,//' "$out/journal_0" > "$out/journal_1"
    ;;
  *) echo "unknown corpus kind $kind" >&2; exit 2 ;;
esac
