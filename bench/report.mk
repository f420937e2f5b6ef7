# report.mk — make report: every method's speed against its error, from a
# sweep file (included by the Makefile; docs/usage.md, "make report").
#
#   make report [SWEEP=f] [FAST=1] [REPORT=dir] [BIN=dir]   -> $(REPORT)/index.html
#   make readme-figures                                      the report's tables in docs/figures.md
#
# bench/report_rules.sh turns the sweep into $(REPORT)/rules.mk: one rule per
# bake configuration (a recursive make of the bake rules above into
# $(REPORT)/bake/CONFIG, TIME_BAKE=1), per reference image and noise floor,
# and per point (bench/report_point.sh); bench/report_finish.sh gathers the
# rows into results.csv, the plots and index.html. make's timestamps make it
# incremental: a second run with nothing changed bakes and renders nothing.
# With BIN given on the command line the tools there are used as they are:
# nothing is built (no "make all"; in the bake sub-makes, REPORT_BAKE=1, the
# tools are files without prerequisites, and each gets -o).

REPORT ?= report
SWEEP ?= $(if $(FAST),bench/report-fast.sweep,bench/report.sweep)
REPORT_BIN_GIVEN := $(filter command line,$(origin BIN))
REPORT_TOOL_NAMES := voxelize thin segment photons cluster reference imgdiff scene-info gbview \
    atlas lightmap
REPORT_OLD_TOOLS := $(if $(REPORT_BIN_GIVEN),$(REPORT_TOOL_NAMES:%=-o $(BIN)/%))
# A rule's prerequisite on a tool, only when this make builds the tools.
report_tool = $(if $(REPORT_BIN_GIVEN),,$(BIN)/$(1))
# In the bake sub-makes with BIN given: the tools are files with no
# prerequisites (make's -o alone would still remake what they are built from,
# in $(BUILD), which may be another build's folder).
ifneq ($(REPORT_BIN_GIVEN),)
ifneq ($(REPORT_BAKE),)
$(addprefix $(BIN)/,voxelize thin segment photons cluster): ;
endif
endif

.PHONY: report report-bakes report-run readme-figures
report:
	$(if $(REPORT_BIN_GIVEN),,+$(MAKE) all)
	+$(MAKE) --no-print-directory REPORT_STAGE=bake report-bakes
	+$(MAKE) --no-print-directory REPORT_STAGE=run report-run

ifneq ($(REPORT_STAGE),)
# The rules of the sweep; make remakes this file first when the sweep or the
# generator changed (and then reads it again).
include $(REPORT)/rules.mk
$(REPORT)/rules.mk: $(SWEEP) bench/report_rules.sh
	@mkdir -p $(@D)
	sh bench/report_rules.sh $(SWEEP) $(REPORT) >$@.tmp && mv $@.tmp $@

report-run: $(REPORT)/results.csv
	@echo "make report: $(REPORT)/index.html, $(REPORT)/results.csv"

# The lightmap's error against its bake's CPU time (bench/lightmap.sh, on
# McGuire's box at 512^2), in the full report only: its truth alone takes
# minutes. index.html shows lightmap.md; lightmap.csv has the rows.
ifeq ($(FAST),)
$(REPORT)/results.csv: $(REPORT)/lightmap.md
$(REPORT)/lightmap.md: bench/lightmap.sh $(if $(REPORT_BIN_GIVEN),,$(BUILD)/bench/lightmap_error) \
    $(foreach t,photons cluster atlas lightmap,$(call report_tool,$(t)))
	LIGHTMAP_CSV=$(REPORT)/lightmap.csv GB_BIN=$(BIN) sh bench/lightmap.sh >$@.tmp
	mv $@.tmp $@
endif
endif

# Two stages. GNU make (4.3) remakes every target whose prerequisite had its
# recipe run, even when that recipe left the file as it was; so a bake file
# whose rule is a recursive make that always runs would re-render every point
# on it. Stage "bake" runs the recursive make of each bake configuration
# (phony report-bake/CONFIG, it does nothing when the bake is fresh) and the
# references that need no bake; stage "run" then sees the bake files as plain
# files with no rule, and renders only the points older than them.

readme-figures:
	+$(MAKE) report
	sh bench/report_readme.sh $(REPORT)/readme-table.md docs/figures.md report
	sh bench/report_readme.sh $(REPORT)/readme-segment-table.md docs/figures.md segment
	sh bench/report_readme.sh $(REPORT)/lightmap.md docs/figures.md lightmap
