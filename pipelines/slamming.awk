# pipelines/slamming.awk - the vertical slamming force on a symmetric 2-D wedge entering still
# water, by Wagner-type theory, at the wedge's own penetration history.
#
#   awk -v tanb=TAN_BETA -v rho=RHO -v halfb=B/2 -f pipelines/slamming.awk IN.tsv
#
# IN.tsv rows (no header): t (s), h (m: penetration of the apex below the still-water level),
# hd (m/s: dh/dt, positive downwards), hdd (m/s^2: d2h/dt2). Each row is printed back as
#   t  h  c  F_mlm  F_wagner  F_karman
# in SI units, forces in N per metre of span (upwards on the wedge):
#   c         the wetted half-width by Wagner's condition for a wedge, c = (pi/2) h / tan(beta)
#             (independent of the speed's history for a wedge);
#   F_mlm     the modified Logvinovich model (Korobkin 2004, "Analytical models of water
#             impact", Eur. J. Appl. Math. 15:821-838): Wagner's flat-plate potential, taken
#             to the body surface by one Taylor term, phi = -hd (sqrt(c^2 - x^2) + f(x) - h),
#             with f(x) = |x| tan(beta), and the full Bernoulli equation on the body, which gives
#               p/rho = hdd (sqrt(c^2-x^2) + f - h) + hd c cd / sqrt(c^2-x^2)
#                       - hd^2 / 2 - hd^2 x^2 / (2 (c^2 - x^2) (1 + f'^2)),    cd = dc/dt,
#             integrated over the wetted width where p >= 0 (it turns negative close to c);
#   F_wagner  Wagner's (1932) flat-plate force d(m_a hd)/dt, m_a = rho pi c^2 / 2: the known
#             over-estimate (it keeps the 1/sqrt singularity up to c, no Bernoulli loss);
#   F_karman  von Karman's (1929) force, the same added mass with c = h / tan(beta) (no
#             pile-up of the water): the known under-estimate.
# The exact (similarity) solution of a wedge at constant speed lies between the last two.
# After the chines are wetted (c > halfb) none of these applies: the row's forces are "-".
BEGIN { FS = "\t"; OFS = "\t"; pi = atan2(0, -1); if (tanb <= 0 || rho <= 0 || halfb <= 0) exit 2 }
# p/rho at x = c sin(th), times dx/dth = c cos(th) (finite for th < pi/2)
function integrand(th,   x, s, p) {
    x = C * sin(th); s = C * cos(th)
    p = HDD * (s + x * tanb - H) + HD * C * CD / s - HD * HD / 2
    p -= HD * HD * x * x / (2 * s * s * (1 + tanb * tanb))
    return p * s
}
function pressure(th) { return integrand(th) / (C * cos(th)) }
function mlm(h, hd, hdd,   lo, hi, mid, i, n, dth, sum) {
    H = h; HD = hd; HDD = hdd; C = pi / 2 * h / tanb; CD = pi / 2 * hd / tanb
    if (h <= 0 || C <= 0) return 0
    if (pressure(0) <= 0) return 0
    lo = 0; hi = pi / 2 * (1 - 1e-12)              # p(lo) > 0 > p(hi): bisect for p = 0
    for (i = 0; i < 80; i++) { mid = (lo + hi) / 2; if (pressure(mid) > 0) lo = mid; else hi = mid }
    n = 2000; dth = lo / n; sum = integrand(0) + integrand(lo)   # Simpson's rule over [0, th*]
    for (i = 1; i < n; i++) sum += (i % 2 ? 4 : 2) * integrand(i * dth)
    return 2 * rho * sum * dth / 3                 # both faces
}
{
    t = $1; h = $2; hd = $3; hdd = $4
    c = pi / 2 * h / tanb
    if (h <= 0) { print t, h, 0, 0, 0, 0; next }
    if (c > halfb) { print t, h, c, "-", "-", "-"; next }
    fw = rho * pi * (c * pi / 2 * hd / tanb * hd + c * c / 2 * hdd)    # d(rho pi c^2/2 hd)/dt
    ck = h / tanb
    fk = rho * pi * (ck * hd / tanb * hd + ck * ck / 2 * hdd)
    printf "%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\n", t, h, c, mlm(h, hd, hdd), fw, fk
}
