#!/usr/bin/env bash
# Markdown table of a gasp-pairs --csv run beside the paper's numbers (docs/benchmarks.md).
#   scripts/benchmarks_table.sh RUN.csv PAPER_DATASET SKIP_MAP [PAPER_CSV]
# PAPER_DATASET: cabinet | household | structure_notexture (../shared/paper/table11_paper.csv).
# SKIP_MAP: our skip -> the paper's frame skip, e.g. "1:20,2:40" (cabinet keyframes) or
# "10:10,50:50,100:100"; skips without an entry get no paper column value.
# A method of the run's other skips missing at some skip is printed "n/a (no rgb)" (gasp-pairs
# leaves colour methods out of pairs without rgb and writes no CSV row for them).
set -euo pipefail
RUN=$1
DATASET=$2
MAP=$3
PAPER=${4:-$(dirname "$0")/../../shared/paper/table11_paper.csv}
[ -f "$PAPER" ] || PAPER=/dev/null
awk -F, -v dataset="$DATASET" -v map="$MAP" '
  BEGIN {
    n = split(map, pairs, ",");
    for (k = 1; k <= n; ++k) { split(pairs[k], kv, ":"); paper_skip[kv[1]] = kv[2]; }
    name["gasp"] = "GASP"; name["gasp-norefine"] = "GASP"; name["fpfh"] = "FPFH"; name["shot"] = "SHOT";
    name["cshot"] = "C-SHOT"; name["sift"] = "SIFT"; name["dsift"] = "D-SIFT";
  }
  FNR == 1 { next }
  FILENAME != ARGV[2] && $1 == dataset { paper[$2 "," $3] = sprintf("%.3f / %.2f / %.1f", $4, $5, $6); next }
  FILENAME == ARGV[2] {
    if (!($1 in seen_skip)) { seen_skip[$1] = 1; skips[++ns] = $1; }
    if (!($2 in seen_method)) { seen_method[$2] = 1; methods[++nm] = $2; }
    if ($4 == $3) row[$1 "," $2] = sprintf("%d | %d | - | - | %.1f | %.1f | %.0f", $3, $4, $7, $8, $9);  # no estimate
    else row[$1 "," $2] = sprintf("%d | %d | %.4f | %.2f | %.1f | %.1f | %.0f", $3, $4, $5, $6, $7, $8, $9);
  }
  END {
    print "| skip | method | pairs | failed | RMSE t [m] | RMSE r [deg] | fail % | within 5 cm / 2 deg % | median ms / pair | paper: skip, t / r / fail |";
    print "|---|---|---|---|---|---|---|---|---|---|";
    for (s = 1; s <= ns; ++s)
      for (m = 1; m <= nm; ++m) {
        sk = skips[s]; me = methods[m];
        ps = (sk in paper_skip) ? paper_skip[sk] : "";
        pv = (ps != "" && (ps "," name[me]) in paper) ? ps ": " paper[ps "," name[me]] : "";
        if ((sk "," me) in row) printf "| %s | %s | %s | %s |\n", sk, me, row[sk "," me], pv;
        else printf "| %s | %s | n/a (no rgb) | | | | | | | %s |\n", sk, me, pv;
      }
  }' "$PAPER" "$RUN"
