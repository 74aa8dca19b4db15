# pipelines/demo.mk - the demo pipeline: every shipped case through gencase, info and vtk.
#
#   make -f pipelines/demo.mk            (from the top of the tree; `make demo` does this)
#   make -f pipelines/demo.mk clean
#
# For each case directory cases/NAME/ holding a GenCase file (NAME_Def.xml, else the first
# *_Def.xml there):
#   cases/NAME/NAME_Def.xml --vres-gencase--> demo/NAME/NAME.h5 --vres-info--> demo/NAME/info.txt
#                                              demo/NAME/NAME.h5 --vres-vtk--> demo/vtk/NAME.vtu
# and demo/vtk/cases.pvd collects the .vtu files for ParaView, one case per time step
# (0, 1, 2, ... in alphabetical order of NAME), so the time control steps through the cases,
# which share coordinates and would otherwise be drawn on top of each other.
# Every step depends on its input and on the tool that makes it, so a re-run redoes only
# what changed. The tools write their outputs atomically (vres-info through -o); the two
# files written here go through a temporary name too.

BIN      := bin
GENCASE  := $(BIN)/vres-gencase
INFO     := $(BIN)/vres-info
VTK      := $(BIN)/vres-vtk
DEMO     := demo

# Case directories with a case file, and the case file of each; benchmark scenes (bench_*, a
# million particles) are left to make bench.
CASE_XMLS := $(wildcard cases/*/*_Def.xml)
NAMES     := $(filter-out bench_%,$(sort $(notdir $(patsubst %/,%,$(dir $(CASE_XMLS))))))
xml_of     = $(firstword $(wildcard cases/$(1)/$(1)_Def.xml) $(sort $(wildcard cases/$(1)/*_Def.xml)))

STORES := $(foreach n,$(NAMES),$(DEMO)/$(n)/$(n).h5)
INFOS  := $(foreach n,$(NAMES),$(DEMO)/$(n)/info.txt)
VTUS   := $(foreach n,$(NAMES),$(DEMO)/vtk/$(n).vtu)

all: $(INFOS) $(DEMO)/vtk/cases.pvd

# The rules of one case (make has no pattern rule with the stem twice in one path).
define case_rules
$(DEMO)/$(1)/$(1).h5: $(call xml_of,$(1)) $(GENCASE)
	@mkdir -p $$(@D)
	$(GENCASE) $$< -o $$@

$(DEMO)/$(1)/info.txt: $(DEMO)/$(1)/$(1).h5 $(INFO)
	$(INFO) $$< -o $$@

$(DEMO)/vtk/$(1).vtu: $(DEMO)/$(1)/$(1).h5 $(VTK)
	@mkdir -p $$(@D)
	$(VTK) $$< -o $$@
endef
$(foreach n,$(NAMES),$(eval $(call case_rules,$(n))))

# The list of cases, rewritten only when it changes (a case directory added or removed), so
# that the collection below follows the list without being rewritten on every run.
$(DEMO)/vtk/cases.list: FORCE
	@mkdir -p $(@D)
	@echo '$(NAMES)' > $@.tmp; if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; fi

# The collection: rewritten when a .vtu or the list of cases changes.
$(DEMO)/vtk/cases.pvd: $(VTUS) $(DEMO)/vtk/cases.list pipelines/demo.mk
	@mkdir -p $(@D)
	@{ printf '<?xml version="1.0"?>\n'; \
	   printf '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n  <Collection>\n'; \
	   i=0; for n in $(NAMES); do \
	     printf '    <DataSet timestep="%d" part="0" name="%s" file="%s.vtu"/>\n' $$i $$n $$n; \
	     i=$$((i + 1)); done; \
	   printf '  </Collection>\n</VTKFile>\n'; } > $@.tmp && mv $@.tmp $@
	@echo "$@: $(words $(NAMES)) cases: $(NAMES)"

# A missing tool is built by the top Makefile (an outdated one is rebuilt by `make demo`).
$(BIN)/vres-%:
	$(MAKE) --no-print-directory $@

clean:
	rm -rf $(DEMO)

.PHONY: all clean FORCE
FORCE:
.DELETE_ON_ERROR:
