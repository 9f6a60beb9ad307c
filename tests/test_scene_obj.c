/* test_scene_obj.c - the OBJ reader's vertex splitting against a
 * reference written here the plain way: every corner's (position, normal)
 * pair looked up by a linear search over the pairs met so far, vertices
 * numbered in the order of their first corner (the order the reader has
 * always produced, so a mesh's vertex order never changes). The files are
 * written by the test from arrays it keeps, so the reference needs no
 * OBJ parser of its own. Also: a line reader bounded on a stream with no
 * newline, and one position with many normals (the case that used to be
 * quadratic) giving the right counts.
 */
#include "tst.h"
#include "scene/scene.h"
#include <stdint.h>
#include <unistd.h>

static char tmpdir[256];

/* A mesh as the test knows it: positions, normals, polygons of corners
 * (v, n) with n = -1 for none, 0-based. */
typedef struct { int v, n; } corner;
typedef struct {
    int np, nn, nf;
    double (*p)[3], (*nv)[3];
    int *fstart, *flen;          /* [nf] */
    corner *c;                   /* all corners */
    int neg;                     /* write indices from the end (negative) */
} omesh;

static const char *write_obj(const char *name, const omesh *o)
{
    static char path[400];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    if (!f) return NULL;
    fprintf(f, "# written by test_scene_obj\nvt 0 0\n");
    for (int i = 0; i < o->np; i++) fprintf(f, "v %.17g %.17g %.17g\n", o->p[i][0], o->p[i][1], o->p[i][2]);
    for (int i = 0; i < o->nn; i++) fprintf(f, "vn %.17g %.17g %.17g\n", o->nv[i][0], o->nv[i][1], o->nv[i][2]);
    for (int k = 0; k < o->nf; k++) {
        fputc('f', f);
        for (int j = 0; j < o->flen[k]; j++) {
            corner c = o->c[o->fstart[k] + j];
            int v = o->neg && (j & 1) ? c.v - o->np : c.v + 1;
            int n = o->neg && (j & 1) ? c.n - o->nn : c.n + 1;
            if (c.n < 0) fprintf(f, (k + j) % 2 ? " %d" : " %d/1", v);
            else fprintf(f, (k + j) % 2 ? " %d//%d" : " %d/1/%d", v, n);
        }
        fputc('\n', f);
    }
    return fclose(f) ? NULL : path;
}

/* Read the file and compare with the reference: same vertex count and
 * order, same positions bit for bit, the given normals normalized, same
 * triangles (fans c0 ci ci+1). */
static void check(const char *name, const omesh *o)
{
    const char *path = write_obj(name, o);
    TST_CHECK(path != NULL, "cannot write %s", name);
    if (!path) return;
    scn_mesh m;
    char err[512];
    if (scn_mesh_obj(path, &m, err, sizeof err)) { TST_CHECK(0, "%s: %s", name, err); return; }
    int ntri = 0;
    for (int k = 0; k < o->nf; k++) ntri += o->flen[k] - 2;
    corner *pairs = malloc(sizeof *pairs * (size_t)(3 * ntri));
    int npairs = 0, bad = 0;
    TST_EQ_INT(m.nt, ntri);
    for (int k = 0, t = 0; k < o->nf && (size_t)t < m.nt; k++)
        for (int j = 1; j + 1 < o->flen[k]; j++, t++) {
            corner tc[3] = { o->c[o->fstart[k]], o->c[o->fstart[k] + j], o->c[o->fstart[k] + j + 1] };
            for (int q = 0; q < 3; q++) {
                int e = 0;
                while (e < npairs && (pairs[e].v != tc[q].v || pairs[e].n != tc[q].n)) e++;
                if (e == npairs) pairs[npairs++] = tc[q];
                if (m.tri[t][q] != (uint32_t)e) bad++;
            }
        }
    TST_EQ_INT(m.nv, npairs);
    TST_CHECK(bad == 0, "%s: %d triangle corners differ from the reference's numbering", name, bad);
    int pbad = 0, nbad = 0;
    for (int e = 0; e < npairs && (size_t)e < m.nv; e++) {
        const double *P = o->p[pairs[e].v];
        if (memcmp(m.pos[e], P, sizeof m.pos[e])) pbad++;
        if (pairs[e].n < 0) continue;
        const double *N = o->nv[pairs[e].n];
        double l = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
        if (l == 0) continue;    /* falls back to the computed normal */
        for (int q = 0; q < 3; q++)
            if (!(fabs(m.nrm[e][q] - N[q] / l) <= 1e-15)) { nbad++; break; }
    }
    TST_CHECK(pbad == 0, "%s: %d positions differ", name, pbad);
    TST_CHECK(nbad == 0, "%s: %d normals differ", name, nbad);
    free(pairs);
    scn_mesh_free(&m);
}

static omesh om_new(int np, int nn, int nf, int ncorners)
{
    omesh o = { np, nn, nf, calloc((size_t)np, sizeof *o.p), calloc((size_t)(nn ? nn : 1), sizeof *o.nv),
                calloc((size_t)nf, sizeof(int)), calloc((size_t)nf, sizeof(int)),
                calloc((size_t)ncorners, sizeof(corner)), 0 };
    return o;
}

static void om_free(omesh *o) { free(o->p); free(o->nv); free(o->fstart); free(o->flen); free(o->c); }

static uint64_t rng = 0x243f6a8885a308d3ull;
static unsigned rnd(unsigned n)
{
    rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
    return (unsigned)(rng % n);
}

/* Random polygons over a grid of positions, each corner with a random
 * normal, none, or the zero normal; some indices written negative. */
static void t_obj_random(void)
{
    if (!mkdtemp(strcpy(tmpdir, "/tmp/shadesim-obj-XXXXXX"))) TST_SKIP("no temporary directory");
    for (int round = 0; round < 6; round++) {
        int g = 4 + round * 3, np = g * g, nn = 1 + round * 7, nf = (g - 1) * (g - 1);
        omesh o = om_new(np, nn, nf, 4 * nf);
        o.neg = round & 1;
        for (int i = 0; i < np; i++) {
            o.p[i][0] = (i % g) * 0.25 - 1;
            o.p[i][1] = (i / g) * 0.25 - 1;
            o.p[i][2] = rnd(1000) * 1e-4;
        }
        for (int i = 0; i < nn; i++) {
            o.nv[i][0] = (double)rnd(200) / 100 - 1;
            o.nv[i][1] = (double)rnd(200) / 100 - 1;
            o.nv[i][2] = i == 0 ? 0 : 1;
        }
        if (nn) o.nv[0][0] = o.nv[0][1] = 0;    /* a zero normal */
        int cc = 0;
        for (int y = 0, k = 0; y < g - 1; y++)
            for (int x = 0; x < g - 1; x++, k++) {
                int a = y * g + x, quad = rnd(3) != 0;
                int vs[4] = { a, a + 1, a + g + 1, a + g };
                o.fstart[k] = cc;
                o.flen[k] = quad ? 4 : 3;
                for (int j = 0; j < o.flen[k]; j++) {
                    int r = (int)rnd(4);
                    o.c[cc].v = vs[j];
                    o.c[cc].n = r == 0 ? -1 : (int)rnd((unsigned)nn);
                    cc++;
                }
            }
        char name[32];
        snprintf(name, sizeof name, "rnd%d.obj", round);
        check(name, &o);
        om_free(&o);
    }
}

/* The built-in meshes, written as OBJ with one normal per vertex and a
 * normal list that repeats (several positions share normal indices, one
 * position several normals): the reader's numbering against the
 * reference's on real shapes. */
static void t_obj_builtins(void)
{
    if (!tmpdir[0] && !mkdtemp(strcpy(tmpdir, "/tmp/shadesim-obj-XXXXXX"))) TST_SKIP("no temporary directory");
    for (int b = 0; scn_mesh_builtin_names[b]; b++) {
        scn_mesh m;
        char err[512];
        if (scn_mesh_builtin(scn_mesh_builtin_names[b], 1, &m, err, sizeof err)) { TST_CHECK(0, "%s", err); continue; }
        omesh o = om_new((int)m.nv, (int)m.nv, (int)m.nt, 3 * (int)m.nt);
        memcpy(o.p, m.pos, m.nv * sizeof *o.p);
        memcpy(o.nv, m.nrm, m.nv * sizeof *o.nv);
        for (size_t t = 0; t < m.nt; t++) {
            o.fstart[t] = 3 * (int)t;
            o.flen[t] = 3;
            for (int q = 0; q < 3; q++) {
                uint32_t v = m.tri[t][q];
                o.c[3 * t + q].v = (int)v;
                o.c[3 * t + q].n = (int)(t % 5 == 0 ? (v + 1) % m.nv : v);
            }
        }
        char name[64];
        snprintf(name, sizeof name, "builtin-%s.obj", scn_mesh_builtin_names[b]);
        check(name, &o);
        om_free(&o);
        scn_mesh_free(&m);
    }
}

/* One position triple with N normals: 3 N vertices, N triangles (the
 * shape that made the old list walk quadratic). */
static void t_obj_many_normals(void)
{
    if (!tmpdir[0] && !mkdtemp(strcpy(tmpdir, "/tmp/shadesim-obj-XXXXXX"))) TST_SKIP("no temporary directory");
    int N = 4000;
    omesh o = om_new(3, N, N, 3 * N);
    o.p[1][0] = 1;
    o.p[2][1] = 1;
    for (int k = 0; k < N; k++) {
        o.nv[k][2] = 1 + k % 3;
        o.fstart[k] = 3 * k;
        o.flen[k] = 3;
        for (int q = 0; q < 3; q++) o.c[3 * k + q] = (corner){ q, k };
    }
    check("many-normals.obj", &o);
    om_free(&o);
}

static void t_obj_no_newline(void)
{
    scn_mesh m;
    char err[512];
    if (access("/dev/zero", R_OK)) TST_SKIP("no /dev/zero");
    TST_EQ_INT(scn_mesh_obj("/dev/zero", &m, err, sizeof err), -1);
    TST_CHECK(strstr(err, "/dev/zero:1: binary data") != NULL, "err = %s", err);
    if (!tmpdir[0] && !mkdtemp(strcpy(tmpdir, "/tmp/shadesim-obj-XXXXXX"))) TST_SKIP("no temporary directory");
    char path[400];
    snprintf(path, sizeof path, "%s/long.obj", tmpdir);
    FILE *f = fopen(path, "w");
    fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3", f);
    for (int i = 0; i < (1 << 20) / 2; i++) fputs(" 1", f);
    fclose(f);
    TST_EQ_INT(scn_mesh_obj(path, &m, err, sizeof err), -1);
    TST_CHECK(strstr(err, "long.obj:4: line longer than 1048576 bytes") != NULL, "err = %s", err);
}

static void cleanup(void)
{
    if (!tmpdir[0]) return;
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd)) {}
}

int main(void)
{
    TST_RUN(t_obj_random);
    TST_RUN(t_obj_builtins);
    TST_RUN(t_obj_many_normals);
    TST_RUN(t_obj_no_newline);
    cleanup();
    TST_EXIT();
}
