/* test_field.c - the per-particle field table (lib/field.h): each row names the vres_domain
 * member it says (its pointer, its element size), rows are in the enum's order, the state
 * fields are position, velocity and density; the stored rows are the particle datasets of
 * man/man5/vres-store.5's table, in its order, with its types, shapes and units; and a
 * particle copy moves every field. */
#include <check.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check_run.h"
#include "field.h"
#include "store.h"

START_TEST(rows_name_their_members)
{
    vres_domain d;
    memset(&d, 0, sizeof d);
    vres_domain_reserve(&d, 4);
    void *const want[VRES_NFIELDS] = {d.pos, d.vel, d.rho, d.press, d.mass_p, d.type, d.mk, d.id, d.normal};
    const size_t size[VRES_NFIELDS] = {3 * sizeof *d.pos,  3 * sizeof *d.vel,    sizeof *d.rho,
                                       sizeof *d.press,    sizeof *d.mass_p,     sizeof *d.type,
                                       sizeof *d.mk,       sizeof *d.id,         3 * sizeof *d.normal};
    static const char *const member[VRES_NFIELDS] = {"pos", "vel", "rho", "press", "mass_p", "type", "mk", "id",
                                                     "normal"};
    for (int k = 0; k < VRES_NFIELDS; k++) {
        const vres_field *f = &vres_fields[k];
        ck_assert_ptr_eq(vres_field_array(&d, f), want[k]);
        ck_assert_ptr_eq(*vres_field_slot(&d, f), want[k]);
        ck_assert_uint_eq(f->elem, size[k]);
        ck_assert_str_eq(f->member, member[k]);
        ck_assert_int_eq(f->state, k == VRES_FIELD_POS || k == VRES_FIELD_VEL || k == VRES_FIELD_RHO);
    }
    vres_domain_free(&d);
    for (int k = 0; k < VRES_NFIELDS; k++) ck_assert_ptr_null(vres_field_array(&d, &vres_fields[k]));
}
END_TEST

/* The type column of man5 for a field's kind. */
static const char *man_type(vres_field_kind k)
{
    static const char *const name[] = {"f64", "f32", "u8", "i32", "u64"};
    return name[k];
}

START_TEST(stored_rows_are_the_man_page_datasets)
{
    FILE *f = fopen("man/man5/vres-store.5", "r");
    ck_assert_msg(f != NULL, "man/man5/vres-store.5 (tests run from the repository root)");
    char line[512];
    int on = 0, k = 0;
    while (fgets(line, sizeof line, f)) {
        if (strstr(line, "Datasets, one row per particle")) on = 1;
        if (!on) continue;
        if (!strncmp(line, ".TE", 3)) break;
        if (strncmp(line, "\\fB", 3) != 0) continue;
        char name[64], type[16], shape[32], meaning[256];
        ck_assert_int_eq(sscanf(line, "\\fB%63[^\\]\\fR\t%15[^\t]\t%31[^\t]\t%255[^\n]", name, type, shape, meaning),
                         4);
        while (k < VRES_NFIELDS && !vres_fields[k].dataset) k++; /* rows that are not stored */
        ck_assert_int_lt(k, VRES_NFIELDS);
        const vres_field *fd = &vres_fields[k++];
        ck_assert_str_eq(name, fd->dataset);
        ck_assert_str_eq(type, man_type(fd->kind));
        ck_assert_str_eq(shape, fd->ncomp == 3 ? "\\fIn\\fR x 3" : "\\fIn\\fR");
        if (*fd->unit) {
            char unit[32];
            snprintf(unit, sizeof unit, "(%s)", fd->unit);
            ck_assert_msg(strstr(meaning, unit) || !strcmp(fd->dataset, "Normal"), "%s: man page says '%s', table %s",
                          name, meaning, unit);
        }
    }
    fclose(f);
    while (k < VRES_NFIELDS && !vres_fields[k].dataset) k++;
    ck_assert_int_eq(k, VRES_NFIELDS); /* every stored row is in the man page */
}
END_TEST

START_TEST(copy_particle_moves_every_field)
{
    vres_domain a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    vres_domain_reserve(&a, 3);
    vres_domain_reserve(&b, 3);
    a.n = b.n = 3;
    for (int k = 0; k < VRES_NFIELDS; k++) { /* distinct bytes everywhere */
        unsigned char *p = vres_field_array(&a, &vres_fields[k]), *q = vres_field_array(&b, &vres_fields[k]);
        for (size_t j = 0; j < 3 * vres_fields[k].elem; j++) p[j] = (unsigned char)(17 * k + j + 1), q[j] = 0;
    }
    vres_field_copy_particle(&b, 0, &a, 2);
    for (int k = 0; k < VRES_NFIELDS; k++) {
        const vres_field *f = &vres_fields[k];
        const char *p = vres_field_array(&a, f), *q = vres_field_array(&b, f);
        ck_assert(memcmp(q, p + 2 * f->elem, f->elem) == 0);
        for (size_t j = f->elem; j < 3 * f->elem; j++) ck_assert_int_eq(q[j], 0);
    }
    vres_domain_free(&a);
    vres_domain_free(&b);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("field");
    TCase *tc = tcase_create("field");
    tcase_add_test(tc, rows_name_their_members);
    tcase_add_test(tc, stored_rows_are_the_man_page_datasets);
    tcase_add_test(tc, copy_particle_moves_every_field);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
