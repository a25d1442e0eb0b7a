/* The compiled reference of bench_integrator.py: the Frenet–Serret equations integrated
 * by the sixth-order Magnus method, one step per sample, in a plain C loop.
 *
 * Input: the step h and κ, τ at the three Gauss–Legendre nodes of every step, (n − 1, 3)
 * row-major (evaluated by the caller, as curvefold evaluates a user's functions); the curve
 * starts from the identity frame at the origin. The body twist of (F, x)' = (F, x) ξ is ξ = (τ, 0, κ ; 1, 0, 0); each step
 * takes the twists A_i at the three Gauss–Legendre nodes, forms the Magnus twist
 *
 *   α₁ = A₂, α₂ = (√15/3)(A₃ − A₁), α₃ = (10/3)(A₃ − 2A₂ + A₁),
 *   C₁ = [α₁, α₂], C₂ = −[α₁, 2α₃ + C₁]/60,
 *   Ω = α₁ + α₃/12 + [−20α₁ − α₃ + C₁, α₂ + C₂]/240,
 *
 * with the bracket of a right-multiplied motion, [X, Y] = (Y_ω × X_ω, Y_ω × X_v − X_ω × Y_v),
 * takes its exponential in closed form (a unit quaternion and a translation), and moves the
 * frame's quaternion and the position by it. The quaternion is normalised after every step.
 *
 * Output: points (n, 3) and frames (n, 3, 3) with columns T, N, B, row-major.
 */
#include <math.h>

typedef struct { double w[3], v[3]; } twist;

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static twist bracket(twist x, twist y)
{
    twist out;
    double a[3], b[3];
    cross(y.w, x.w, out.w);
    cross(y.w, x.v, a);
    cross(x.w, y.v, b);
    for (int i = 0; i < 3; i++) out.v[i] = a[i] - b[i];
    return out;
}

static twist combine(double a, twist x, double b, twist y)
{
    twist out;
    for (int i = 0; i < 3; i++) {
        out.w[i] = a * x.w[i] + b * y.w[i];
        out.v[i] = a * x.v[i] + b * y.v[i];
    }
    return out;
}

static twist scaled(double a, twist x)
{
    twist out;
    for (int i = 0; i < 3; i++) {
        out.w[i] = a * x.w[i];
        out.v[i] = a * x.v[i];
    }
    return out;
}

static twist frenet_twist(double h, double kappa, double tau)
{
    twist out = {{h * tau, 0.0, h * kappa}, {h, 0.0, 0.0}};
    return out;
}

static void rotation(const double q[4], double R[9])
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    R[0] = 1.0 - 2.0 * (y * y + z * z); R[1] = 2.0 * (x * y - w * z);       R[2] = 2.0 * (x * z + w * y);
    R[3] = 2.0 * (x * y + w * z);       R[4] = 1.0 - 2.0 * (x * x + z * z); R[5] = 2.0 * (y * z - w * x);
    R[6] = 2.0 * (x * z - w * y);       R[7] = 2.0 * (y * z + w * x);       R[8] = 1.0 - 2.0 * (x * x + y * y);
}

void frenet_magnus6(long n, double h, const double *kappa, const double *tau, double *points, double *frames)
{
    const double k = sqrt(15.0) / 3.0;
    double q[4] = {1.0, 0.0, 0.0, 0.0}, x[3] = {0.0, 0.0, 0.0}, R[9];
    rotation(q, R);
    for (int i = 0; i < 9; i++) frames[i] = R[i];
    for (int i = 0; i < 3; i++) points[i] = 0.0;
    for (long j = 1; j < n; j++) {
        const double *kj = kappa + 3 * (j - 1), *tj = tau + 3 * (j - 1);
        twist A1 = frenet_twist(h, kj[0], tj[0]), A2 = frenet_twist(h, kj[1], tj[1]), A3 = frenet_twist(h, kj[2], tj[2]);
        twist a1 = A2, a2 = combine(k, A3, -k, A1), a3 = combine(10.0 / 3.0, combine(1.0, A3, 1.0, A1), -20.0 / 3.0, A2);
        twist c1 = bracket(a1, a2);
        twist c2 = scaled(-1.0 / 60.0, bracket(a1, combine(2.0, a3, 1.0, c1)));
        twist left = combine(1.0, combine(-20.0, a1, -1.0, a3), 1.0, c1), right = combine(1.0, a2, 1.0, c2);
        twist W = combine(1.0, combine(1.0, a1, 1.0 / 12.0, a3), 1.0 / 240.0, bracket(left, right));

        /* exp: r = (cos θ/2, sin(θ/2)/θ ω), p = v + B ω×v + C ω×(ω×v) */
        double t2 = W.w[0] * W.w[0] + W.w[1] * W.w[1] + W.w[2] * W.w[2], t = sqrt(t2), B, C, half, c;
        if (t < 1e-2) { /* Taylor series, truncation below 1e-22 */
            B = 0.5 - t2 / 24.0 + t2 * t2 / 720.0 - t2 * t2 * t2 / 40320.0;
            C = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0 - t2 * t2 * t2 / 362880.0;
            half = 0.5 - t2 / 48.0 + t2 * t2 / 3840.0 - t2 * t2 * t2 / 645120.0;
            c = 1.0 - t2 / 8.0 + t2 * t2 / 384.0 - t2 * t2 * t2 / 46080.0;
        } else {
            B = (1.0 - cos(t)) / t2;
            C = (t - sin(t)) / (t2 * t);
            half = sin(0.5 * t) / t;
            c = cos(0.5 * t);
        }
        double r[4] = {c, half * W.w[0], half * W.w[1], half * W.w[2]}, wv[3], wwv[3], p[3];
        cross(W.w, W.v, wv);
        cross(W.w, wv, wwv);
        for (int i = 0; i < 3; i++) p[i] = W.v[i] + B * wv[i] + C * wwv[i];

        /* x ← x + R(q) p, q ← q r (normalised) */
        for (int i = 0; i < 3; i++) x[i] += R[3 * i] * p[0] + R[3 * i + 1] * p[1] + R[3 * i + 2] * p[2];
        double u[4] = {
            q[0] * r[0] - q[1] * r[1] - q[2] * r[2] - q[3] * r[3],
            q[0] * r[1] + q[1] * r[0] + q[2] * r[3] - q[3] * r[2],
            q[0] * r[2] - q[1] * r[3] + q[2] * r[0] + q[3] * r[1],
            q[0] * r[3] + q[1] * r[2] - q[2] * r[1] + q[3] * r[0],
        };
        double norm = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2] + u[3] * u[3]);
        for (int i = 0; i < 4; i++) q[i] = u[i] / norm;
        rotation(q, R);
        for (int i = 0; i < 9; i++) frames[9 * j + i] = R[i];
        for (int i = 0; i < 3; i++) points[3 * j + i] = x[i];
    }
}
