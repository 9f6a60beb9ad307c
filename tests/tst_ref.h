/* tst_ref.h - independent references shared by the tests: textbook
 * numerics written without the code under test (no coefficient formulas,
 * no Horner), so that a test compares two different computations. */
#ifndef TST_REF_H
#define TST_REF_H
#include <math.h>

/* Coefficients c (highest degree first) of the polynomial of degree k-1
 * through (t_i, I_i), k <= 4: Gaussian elimination with partial pivoting on
 * the Vandermonde matrix. */
static inline void tst_vander(const double *t, const double *I, int k, double *c)
{
    double m[4][5];
    for (int i = 0; i < k; i++) {
        for (int j = 0; j < k; j++) m[i][j] = pow(t[i], k - 1 - j);
        m[i][k] = I[i];
    }
    for (int col = 0; col < k; col++) {
        int piv = col;
        for (int i = col + 1; i < k; i++) if (fabs(m[i][col]) > fabs(m[piv][col])) piv = i;
        for (int j = 0; j <= k; j++) { double x = m[col][j]; m[col][j] = m[piv][j]; m[piv][j] = x; }
        for (int i = 0; i < k; i++) {
            if (i == col) continue;
            double f = m[i][col] / m[col][col];
            for (int j = col; j <= k; j++) m[i][j] -= f * m[col][j];
        }
    }
    for (int i = 0; i < k; i++) c[i] = m[i][k] / m[i][i];
}

/* Lagrange interpolation through (t_i, I_i), i < k, at x. */
static inline double tst_lagrange(const double *t, const double *I, int k, double x)
{
    double s = 0;
    for (int i = 0; i < k; i++) {
        double w = 1;
        for (int j = 0; j < k; j++) if (j != i) w *= (x - t[j]) / (t[i] - t[j]);
        s += w * I[i];
    }
    return s;
}
#endif
