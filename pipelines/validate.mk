# pipelines/validate.mk - every validation and stability case, checked at its validation
# resolution; one summary table.
#
#   make validate                        (from the top of the tree; runs this file)
#   make validate VALIDATE="hydrostatic_profile2d:0.02 stiff_rest2d:"   (a chosen list)
#   make -j2 -f pipelines/validate.mk THREADS=1 RUNS=build/runs
#   make -f pipelines/validate.mk clean  (removes the runs, keeps the committed summary)
#
# Each entry CASE:DP of VALIDATE runs cases/CASE/check at spacing DP (empty: the case's own)
# into $(RUNS)/validate/CASE-dpDP/, its "key<TAB>value" result lines in CASE-dpDP.result and
# its messages in CASE-dpDP.log. The entries are independent targets, so `make -j2` runs two
# at a time. A run directory that already holds a run is checked again, not rerun (the checks
# only read it); `clean` forces new runs. Then
#   $(RUNS)/validate/summary.tsv     case, dp, particles, steps, run time, error, tolerance,
#                                    verdict: one row per entry, with the command, machine
#                                    and build in its # header
#   pipelines/reports/validate.tsv   a copy, committed as the record of the last full run
# and the summary is printed. make fails when an entry fails (its row says FAIL), after the
# summary is written.
#
# The default list holds the validations whose physics vres-run has and the stability cases
# (DESIGN section 7; the stiff_vres_* ones run coupled, through vres-partition), and the 3-D
# coupled cases end to end: tank_vres3d (still water, 0.3 s: 15 min on one core) and
# dambreak_vres3d (0.8 s coupled and single resolution: see its README.md for the time).
# cavity_re1000 is the longest entry (30 s of flow at L/dp = 40: 27 min on one core of the
# loaded 2-core VM; cases/cavity_re1000/README.md).

BIN     := bin
RUNS    ?= build/runs
THREADS ?= 1
REPORTS ?= pipelines/reports
V       := $(RUNS)/validate

VALIDATE ?= dambreak_front2d:0.02 dambreak_front2d:0.01 hydrostatic_profile2d:0.02 \
            poiseuille2d:5e-5 couette2d:5e-5 poiseuille_mdbc2d:5e-5 cavity_re100:0.02 \
            dambreak_lobovsky2d:0.01 ritter2d:0.05 taylor_green2d:0.02 cavity_re1000:0.025 \
            floating_box2d: floating_heavy2d: wedge: wedge_entry2d: \
            stiff_rest2d: stiff_impact2d: stiff_lowvisc2d: stiff_sps2d: stiff_tinydp2d: stiff_float_light2d: \
            stiff_vres_front2d: stiff_vres_dpratio4_2d: stiff_vres_nested3_2d: stiff_vres_corner2d: \
            stiff_vres_siblings2d: tank_vres3d: dambreak_vres3d: channel_inout2d: poiseuille_inout2d: \
            stiff_inlet_step2d: stiff_inlet_reverse2d: stiff_inout_drain2d:

case_of = $(word 1,$(subst :, ,$(1)))
dp_of   = $(word 2,$(subst :, ,$(1)))
# result file of an entry: CASE-dpDP.result, or CASE-dpcase.result for the case's own dp
res_of  = $(V)/$(call case_of,$(1))-dp$(or $(call dp_of,$(1)),case).result
RESULTS := $(foreach e,$(VALIDATE),$(call res_of,$(e)))

all: $(V)/summary.tsv
	@cat $<
	@cp $< $(REPORTS)/validate.tsv.tmp && mv $(REPORTS)/validate.tsv.tmp $(REPORTS)/validate.tsv
	@! grep -q 'FAIL$$' $<

# The rule of one entry: a failing check still leaves its result (the summary shows FAIL).
define entry_rule
$(call res_of,$(1)): cases/$(call case_of,$(1))/check $(wildcard cases/$(call case_of,$(1))/*_Def.xml) \
                     $(BIN)/vres-gencase $(BIN)/vres-run pipelines/vreslib.sh
	@mkdir -p $$(@D)
	-cases/$(call case_of,$(1))/check --threads $(THREADS) $(if $(call dp_of,$(1)),--dp $(call dp_of,$(1))) \
	  -o $$(basename $$@) >$$@.tmp 2>$$(basename $$@).log; mv $$@.tmp $$@
endef
$(foreach e,$(VALIDATE),$(eval $(call entry_rule,$(e))))

$(V)/summary.tsv: $(RESULTS) pipelines/validate.mk
	@{ printf '# make validate: every validation and stability case at its validation dp (vres-run, CPU)\n'; \
	   printf '# command: make validate VALIDATE="%s" THREADS=$(THREADS) (each entry: cases/CASE/check --threads $(THREADS) --dp DP -o RUNDIR)\n' '$(strip $(VALIDATE))'; \
	   printf '# made: %s on %s (%s CPUs: %s), vres git %s\n' "$$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$$(uname -n)" "$$(nproc)" \
	     "$$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)" "$$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"; \
	   printf '# error and tolerance: as each case defines them (cases/CASE/README.md); stability cases: largest speed over c0, tolerance 1, the fluid mass a condition (stiff_vres_*: largest total mass drift of ledger.tsv, against one particle mass per segment)\n'; \
	   printf '# case\tdp_m\tparticles\tsteps\trun_time_s\terror\ttolerance\tverdict\n'; \
	   for r in $(RESULTS); do \
	     awk -F'\t' -v f="$$r" '{v[$$1] = $$2} END { n = split("case dp_m particles steps run_time_s error tolerance verdict", k, " "); \
	       if (v["case"] == "") { c = f; sub(/.*\//, "", c); sub(/-dp.*/, "", c); v["case"] = c } \
	       if (v["verdict"] == "") v["verdict"] = "FAIL"; \
	       for (i = 1; i <= n; i++) printf "%s%s", (v[k[i]] == "" ? "-" : v[k[i]]), (i < n ? "\t" : "\n") }' "$$r"; \
	   done; } >$@.tmp && mv $@.tmp $@

# A missing tool is built by the top Makefile.
$(BIN)/vres-%:
	$(MAKE) --no-print-directory $@

clean:
	rm -rf $(V)

.PHONY: all clean
.DELETE_ON_ERROR:
