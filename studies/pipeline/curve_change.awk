# Two plate.csv files -> the change of the loading leg, as rigs::curve_change measures it: the second
# curve read at the first one's sinkages where both reach, in five parts; the largest difference of
# the parts' means over the largest mean. Usage: awk -F, -f curve_change.awk A.csv B.csv
FNR == 1 { f++; next }
$4 == "load" { n[f]++; z[f, n[f]] = $2; v[f, n[f]] = $3 }
END {
  m = 0
  for (i = 1; i <= n[1]; i++) {
    x = z[1, i]; if (x < z[2, 1] || x > z[2, n[2]]) continue
    for (k = 1; k < n[2] && z[2, k] < x; k++);
    w = k > 1 && z[2, k] > z[2, k - 1] ? (x - z[2, k - 1]) / (z[2, k] - z[2, k - 1]) : 1
    m++; A[m] = v[1, i]; B[m] = k > 1 ? v[2, k - 1] + w * (v[2, k] - v[2, k - 1]) : v[2, 1]
  }
  d = 0; s = 0
  for (p = 0; p < 5 && m >= 5; p++) {
    lo = int(p * m / 5) + 1; hi = int((p + 1) * m / 5); a = 0; b = 0
    for (i = lo; i <= hi; i++) { a += A[i]; b += B[i] }
    a /= (hi - lo + 1); b /= (hi - lo + 1); x = a > b ? a - b : b - a
    if (x > d) d = x; if (a > s) s = a; if (b > s) s = b
  }
  printf "%.1f %%", (s > 0 ? 100 * d / s : 0)
}
