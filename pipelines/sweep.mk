# pipelines/sweep.mk - error against run time: each validation case at three or more
# resolutions, one table and one plot per case.
#
#   make sweep                                   (from the top of the tree; runs this file)
#   make sweep SWEEP_CASES=hydrostatic_profile2d DPS_hydrostatic_profile2d="0.04 0.02 0.01"
#   make -f pipelines/sweep.mk JOBS=2 THREADS=1 RUNS=build/runs
#   make -f pipelines/sweep.mk clean             (removes the runs, keeps the reports)
#
# For each CASE of SWEEP_CASES, GNU parallel runs cases/CASE/check at each dp of DPS_CASE,
# JOBS at a time with THREADS OpenMP threads each (finest dp first, so the longest run starts
# first), into $(RUNS)/sweep/CASE/dpDP/; each check's "key<TAB>value" lines go to
# dpDP.result and its messages to dpDP.log. Then
#   pipelines/reports/CASE/table.tsv       dp, particles, steps, run time, error, verdict, with
#                                          the command, machine and build in its header and the
#                                          observed order of convergence in a trailing comment
#                                          (pipelines/table.sh); where the reference is an
#                                          experiment, also the convergence of the case against
#                                          itself (pipelines/selfconv.sh, SERIES_CASE)
#   pipelines/reports/CASE/error_vs_time.png   error against run time, log-log (gnuplot)
# A check whose error is above its tolerance still gives its row (verdict FAIL): the table is
# a measurement. A run directory already holding a run is checked again, not rerun; `clean`
# forces new runs. The default list holds the cases whose physics vres-run has; the others are
# named in cases/*/README.md with the feature they wait for.

BIN     := bin
RUNS    ?= build/runs
JOBS    ?= 2
THREADS ?= 1
REPORTS ?= pipelines/reports

SWEEP_CASES ?= dambreak_front2d hydrostatic_profile2d poiseuille2d couette2d cavity_re100 taylor_green2d

# Resolutions per case, coarse to fine. The finest run sets a case's time: on one core of the
# 2-core development VM the dam break at dp 0.01 (23,030 particles, 19,072 steps) took 27 min
# while other jobs shared the machine (4.4e8 particle-steps); every other run took 4.5 min or
# less (pipelines/reports/*/table.tsv).
DPS_dambreak_front2d       ?= 0.04 0.02 0.01
DPS_hydrostatic_profile2d  ?= 0.04 0.02 0.01
DPS_poiseuille2d           ?= 1e-4 5e-5 2.5e-5
DPS_couette2d              ?= 1e-4 5e-5 2.5e-5
DPS_taylor_green2d         ?= 0.04 0.02 0.01
DPS_cavity_re100           ?= 0.05 0.04 0.03125 0.025
# Dam break on the Lobovsky tank (wall pressures) and against Ritter (depth profile); not in the
# default list: `make sweep SWEEP_CASES="dambreak_lobovsky2d ritter2d"`. The finest Lobovsky run
# (dp 0.0075, 4,355 particles, about 16,500 steps to t = 1 s) sets their time; dp 0.005 (8,900
# particles, 25,000 steps) would take three times as long. Measured run times: each case's README.
DPS_dambreak_lobovsky2d    ?= 0.02 0.01 0.0075
DPS_ritter2d               ?= 0.1 0.05 0.025
# Lid-driven cavity at Re = 1000 (not in the default list: `make sweep SWEEP_CASES=cavity_re1000`):
# 30 s of flow each; the finest run (dp 0.025, 5,740 particles with the 30 m lid, 45,396 steps,
# an estimated 8 min on a free core) sets the time. Measured run times: cases/cavity_re1000/README.md.
DPS_cavity_re1000          ?= 0.04 0.03125 0.025

# Where the reference is an experiment, also the case's convergence against itself
# (pipelines/selfconv.sh): the command printing the case's series from a run directory.
SERIES_dambreak_front2d    := pipelines/front.sh --dimensionless
# Ritter's solution is the shallow-water limit, which the computed (non-hydrostatic) flow only
# approaches: the depth profile at the last snapshot (t sqrt(g/h0) = 3) measures the numerics.
SERIES_ritter2d            := cases/ritter2d/profile

all: $(foreach c,$(SWEEP_CASES),$(REPORTS)/$(c)/error_vs_time.png)

# The rules of one case.
define sweep_rules
$(RUNS)/sweep/$(1)/done: cases/$(1)/check $(wildcard cases/$(1)/*_Def.xml) $(BIN)/vres-gencase $(BIN)/vres-run \
                         pipelines/vreslib.sh
	@mkdir -p $$(@D)
	-parallel -j$(JOBS) --halt never \
	  'cases/$(1)/check --threads $(THREADS) --dp {} -o $$(@D)/dp{} >$$(@D)/dp{}.result 2>$$(@D)/dp{}.log' \
	  ::: $$(shell printf '%s\n' $(DPS_$(1)) | sort -g)
	touch $$@

$(REPORTS)/$(1)/table.tsv: $(RUNS)/sweep/$(1)/done pipelines/table.sh pipelines/selfconv.sh
	@mkdir -p $$(@D)
	pipelines/table.sh $(1) \
	  "make sweep SWEEP_CASES=$(1) DPS_$(1)=\"$(DPS_$(1))\" JOBS=$(JOBS) THREADS=$(THREADS) (= parallel -j$(JOBS) cases/$(1)/check --threads $(THREADS) --dp {} -o RUNDIR ::: $(DPS_$(1)))" \
	  $$(foreach d,$(DPS_$(1)),$(RUNS)/sweep/$(1)/dp$$(d).result) >$$@.tmp
	$(if $(SERIES_$(1)),pipelines/selfconv.sh '$(SERIES_$(1))' \
	  $$(foreach d,$(DPS_$(1)),$(RUNS)/sweep/$(1)/dp$$(d):$$(d)) >>$$@.tmp)
	mv $$@.tmp $$@
	@cat $$@

$(REPORTS)/$(1)/error_vs_time.png: $(REPORTS)/$(1)/table.tsv pipelines/error_vs_time.gp
	gnuplot -e "table='$$<'; out='$$@.tmp'; name='$(1)'" pipelines/error_vs_time.gp && mv $$@.tmp $$@
endef
$(foreach c,$(SWEEP_CASES),$(eval $(call sweep_rules,$(c))))

# A missing tool is built by the top Makefile.
$(BIN)/vres-%:
	$(MAKE) --no-print-directory $@

clean:
	rm -rf $(RUNS)/sweep

.PHONY: all clean
.DELETE_ON_ERROR:
