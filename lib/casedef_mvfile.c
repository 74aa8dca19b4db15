/* casedef_mvfile.c - motions read from a table in a file (<mvrectfile>, <mvrotfile> of
 * DualSPHysics' <motion>): the file's columns picked by <file fields fieldtime fieldx ...>,
 * read once by vres-gencase into the segment's table (vres_motion_seg.tab), which the store
 * keeps (/Bodies/B<i>/Table<id>), so that a store runs without the file. A redraw of a
 * sub-domain (vres-partition) takes the table from the root store instead of the file. */
#include "casedef_int.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

/* Rows a table may hold. */
#define MVFILE_MAX_ROWS 10000000

/* The columns a <file> asks for. */
typedef struct mv_cols {
    int fields;  /* columns a row has at least */
    int col[4];  /* column of time, then x, y, z (rect) or angle (rot, col[1]); -1 for none */
} mv_cols;

/* The attributes of <file> e into k for a rectilinear (rot 0) or rotational (rot 1) motion.
 * 0, or -1 after an error. */
static int read_cols(cd_ctx *c, xmlNodePtr e, int rot, mv_cols *k)
{
    static const char *const rattrs[] = {"name", "fields", "fieldtime", "fieldx", "fieldy", "fieldz", NULL};
    static const char *const aattrs[] = {"name", "fields", "fieldtime", "fieldang", NULL};
    if (cd_check_attrs(c, e, rot ? aattrs : rattrs)) return -1;
    const char *const names[4] = {"fieldtime", rot ? "fieldang" : "fieldx", rot ? NULL : "fieldy", rot ? NULL : "fieldz"};
    int top = -1, any = 0;
    for (int a = 0; a < 4; a++) {
        k->col[a] = -1;
        if (!names[a]) continue;
        const int dflt = a == 0 ? 0 : rot && a == 1 ? 1 : -1;
        if (cd_int(c, e, names[a], dflt, &k->col[a]) < 0) return -1;
        if (k->col[a] < -1 || (k->col[a] == -1 && a == 0)) {
            cd_err(c, e, "<file %s=\"%d\">: a column number (0 for the first)", names[a], k->col[a]);
            return -1;
        }
        if (k->col[a] > top) top = k->col[a];
        any |= a > 0 && k->col[a] >= 0;
    }
    if (!any) {
        cd_err(c, e, "<file> names no column of positions (fieldx, fieldy or fieldz)");
        return -1;
    }
    if (cd_int(c, e, "fields", top + 1, &k->fields) < 0) return -1;
    if (k->fields <= top) {
        cd_err(c, e, "<file fields=\"%d\">: fewer columns than the column numbers need (%d)", k->fields, top + 1);
        return -1;
    }
    return 0;
}

/* One value of a row: the token's number into *v. 0, or -1 when it is not a finite number. */
static int token_num(const char *t, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(t, &end);
    return end != t && *end == 0 && errno == 0 && isfinite(*v) ? 0 : -1;
}

/* Read file path's rows into m's table (angles times f for a rotation). 0, or -1 after an error
 * at element e naming the file and its line. */
static int read_rows(cd_ctx *c, xmlNodePtr e, const char *path, const char *shown, const mv_cols *k, int rot,
                     double f, vres_motion_seg *m)
{
    FILE *fp = fopen(path, "r");
    if (!fp) {
        cd_err(c, e, "<file name=\"%s\">: cannot open %s: %s", shown, path, strerror(errno));
        return -1;
    }
    char *line = NULL, *tok[64], *save;
    size_t cap = 0, n = 0, alloc = 0;
    long lineno = 0;
    int bad = 0, data = 0;
    while (!bad && getline(&line, &cap, fp) >= 0) {
        lineno++;
        char *h = strchr(line, '#');
        if (h) *h = 0;
        int nt = 0;
        for (char *t = strtok_r(line, " \t;,\r\n", &save); t && nt < 64; t = strtok_r(NULL, " \t;,\r\n", &save))
            tok[nt++] = t;
        if (nt == 0) continue;
        double v0;
        if (!data && token_num(tok[0], &v0) != 0) continue; /* a header above the rows */
        data = 1;
        if (nt < k->fields) {
            cd_err(c, e, "%s:%ld: %d columns where <file fields=\"%d\"> asks for %d", shown, lineno, nt, k->fields, k->fields);
            bad = 1;
            break;
        }
        double row[4] = {0, 0, 0, 0};
        for (int a = 0; a < 4 && !bad; a++)
            if (k->col[a] >= 0 && token_num(tok[k->col[a]], &row[a]) != 0) {
                cd_err(c, e, "%s:%ld: column %d, '%s', is not a number", shown, lineno, k->col[a], tok[k->col[a]]);
                bad = 1;
            }
        if (bad) break;
        if (n > 0 && !(row[0] > m->tab[4 * (n - 1)])) {
            cd_err(c, e, "%s:%ld: time %g is not after the row before's (%g): times must increase", shown, lineno, row[0],
                   m->tab[4 * (n - 1)]);
            bad = 1;
            break;
        }
        if (n >= MVFILE_MAX_ROWS) {
            cd_err(c, e, "%s: more than %d rows", shown, MVFILE_MAX_ROWS);
            bad = 1;
            break;
        }
        if (n == alloc) {
            alloc = alloc ? 2 * alloc : 64;
            m->tab = vres_xrealloc(m->tab, 4 * alloc * sizeof *m->tab);
        }
        double *r = &m->tab[4 * n++];
        r[0] = row[0];
        if (rot) r[1] = f * row[1], r[2] = r[3] = 0;
        else r[1] = row[1], r[2] = c->dim == 2 ? 0.0 : row[2], r[3] = row[3];
    }
    if (!bad && ferror(fp)) cd_err(c, e, "<file name=\"%s\">: cannot read %s", shown, path), bad = 1;
    if (!bad && n == 0) cd_err(c, e, "<file name=\"%s\">: no rows of numbers in %s", shown, path), bad = 1;
    free(line);
    fclose(fp);
    m->ntab = bad ? 0 : n;
    return bad ? -1 : 0;
}

/* In a redraw: the table of the same body's (mkbound mk) segment of the same id in the root
 * store, copied into m. 0, or -1 after an error. */
static int from_root(cd_ctx *c, xmlNodePtr e, int mk, vres_motion_seg *m)
{
    for (size_t b = 0; b < c->root->nbodies; b++) {
        const vres_body *B = &c->root->body[b];
        if (B->mkbound != mk) continue;
        for (size_t i = 0; i < B->nseg; i++)
            if (B->seg[i].id == m->id && B->seg[i].ntab) {
                m->ntab = B->seg[i].ntab;
                m->tab = vres_xmalloc(4 * m->ntab * sizeof *m->tab);
                memcpy(m->tab, B->seg[i].tab, 4 * m->ntab * sizeof *m->tab);
                return 0;
            }
    }
    cd_err(c, e, "<%s id=\"%d\">: the store holds no table for this segment of mkbound %d (make it again with this "
                 "vres-gencase)", cd_name(e), m->id, mk);
    return -1;
}

int cd_read_mvfile(cd_ctx *c, xmlNodePtr seg, int mk, int rot, double f, vres_motion_seg *m)
{
    xmlNodePtr e = cd_child(seg, "file");
    if (!e) {
        cd_err(c, seg, "<%s> needs <file name=\"...\">", cd_name(seg));
        return -1;
    }
    mv_cols k;
    if (read_cols(c, e, rot, &k) != 0) return -1;
    if (c->root) return from_root(c, seg, mk, m);
    char *name = cd_attr(e, "name");
    if (!name || !*name) {
        cd_err(c, e, "<file> needs the attribute 'name'");
        free(name);
        return -1;
    }
    if (!rot && c->dim == 2 && k.col[2] >= 0)
        cd_note(c, e, "<file fieldy=\"%d\">: a 2D case moves in x and z only; the y column is not used", k.col[2]);
    char *path = name[0] == '/' || !c->dir ? vres_xstrdup(name) : vres_xasprintf("%s/%s", c->dir, name);
    int rc = read_rows(c, e, path, name, &k, rot, f, m);
    if (rc == 0)
        cd_debug(c, seg, "<%s id=\"%d\">: %zu rows from %s, t %g to %g s", cd_name(seg), m->id, m->ntab, path, m->tab[0],
                 m->tab[4 * (m->ntab - 1)]);
    free(path);
    free(name);
    return rc;
}
