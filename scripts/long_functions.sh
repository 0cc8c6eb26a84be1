#!/usr/bin/env bash
# Lists the longest C++ functions of sim/, optimize/, app/ and bench/ with Universal Ctags
# (start and end lines from its JSON output), longest first.
#   bash scripts/long_functions.sh            # threshold 120 lines, top 20
#   bash scripts/long_functions.sh 100        # threshold 100
#   bash scripts/long_functions.sh 120 50     # threshold 120, list the top 50
# Prints the top N functions, then every function over the threshold and the counts.
# Exit status: 1 if any function is longer than the threshold, 0 otherwise, 2 on a usage
# error. Lambdas nested in a function count as part of it, not on their own.
# Needs universal-ctags (Debian: universal-ctags) and /usr/bin/python3 (standard library).
set -euo pipefail
cd "$(dirname "$0")/.."
threshold="${1:-120}"
top="${2:-20}"
if ! [[ "$threshold" =~ ^[0-9]+$ && "$top" =~ ^[0-9]+$ ]]; then
  echo "usage: $0 [THRESHOLD_LINES (default 120)] [TOP_N (default 20)]" >&2
  exit 2
fi
if ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "long_functions: Universal Ctags is needed (apt-get install universal-ctags)" >&2
  exit 2
fi
mapfile -t files < <(find sim optimize app bench -type f \
  \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' \) | LC_ALL=C sort)
ctags --languages=C++ --kinds-C++=f --fields=+neKZ --output-format=json -o - "${files[@]}" |
  /usr/bin/python3 -c '
import json, sys
threshold, top = int(sys.argv[1]), int(sys.argv[2])
funcs = []
for line in sys.stdin:
    t = json.loads(line)
    if t.get("_type") != "tag" or t.get("kind") != "function" or "end" not in t:
        continue
    if t.get("scopeKind") == "function":  # a lambda inside a function: part of that function
        continue
    name = t["name"]
    scope = t.get("scope", "")
    if scope:
        name = scope + "::" + name
    name = "::".join(p for p in name.split("::") if not p.startswith("__anon"))
    n = t["end"] - t["line"] + 1
    funcs.append((n, t["path"], t["line"], t["end"], name))
funcs.sort(key=lambda f: (-f[0], f[1], f[2]))
over = [f for f in funcs if f[0] > threshold]
def show(f):
    print(f"{f[0]:5d}  {f[1]}:{f[2]}-{f[3]}  {f[4]}")
print(f"longest {min(top, len(funcs))} of {len(funcs)} functions (lines, file:start-end, name):")
for f in funcs[:top]:
    show(f)
if len(over) > top:
    print(f"\nfurther functions over {threshold} lines:")
    for f in over[top:]:
        show(f)
print()
for limit in sorted({threshold, 100, 60}, reverse=True):
    print(f"over {limit} lines: {sum(1 for f in funcs if f[0] > limit)}")
sys.exit(1 if over else 0)
' "$threshold" "$top"
