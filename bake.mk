# bake.mk — make bake: voxelize → thin → segment and photons → cluster,
# SCENE (a .scene or a mesh) into $(BAKE)/NAME.*, NAME the scene file's name
# without its last extension (what gbview --bake looks for). Several at once:
# make -j bake SCENES="a.scene b.obj".
#
# Each step reruns exactly when what it reads changed, and only then:
#   NAME.content       scene-info --hash of the scene (content_hash.h), remade
#                      when any file the scene read changed (the .scene, the
#                      mesh, its .mtl, its images: scene-info --depfile, in
#                      NAME.content.d, which make includes);
#   NAME.scene-hash    its scene_hash line, NAME.images-hash its images_hash
#                      line, each rewritten only when the line changes: every
#                      step depends on the scene hash (which every baked file
#                      records), photons also on the images, so an edit of a
#                      camera reruns nothing and of a texture only photons and
#                      cluster;
#   NAME.TOOL-flags    TOOL's flags (VOXELIZE_FLAGS, ...), rewritten only
#                      when they change: changed flags rerun that step and
#                      what follows;
# and each step depends on its tool's binary and the baked files it reads.
# A bake folder holds one scene of a name: NAME.source records which, and a
# second scene of the same name is refused (give it another BAKE).
# TIME_BAKE=1: each step also writes NAME.TOOL.time, GNU time's "wall_s user_s
# sys_s peak_rss_KiB" (make report reads them). BIN: the tools (the Makefile's
# BUILD/bin; make -f bake.mk BIN=DIR bakes with tools built elsewhere).

BAKE ?= bake
BIN ?= build/bin
SCENE ?= scenes/cornell/cornell.scene
SCENES ?= $(SCENE)
SCENE_NAME := $(basename $(notdir $(SCENE)))
VOXELIZE_FLAGS ?=
THIN_FLAGS ?=
SEGMENT_FLAGS ?=
PHOTONS_FLAGS ?=
CLUSTER_FLAGS ?=
ATLAS_FLAGS ?=
LIGHTMAP_FLAGS ?=
SHARDS ?= 1
shard_indices = $(shell seq 0 $$(($(SHARDS) - 1)))
BAKE_MK := $(abspath $(lastword $(MAKEFILE_LIST)))
# The bake steps and the suffix of the file each writes, in their order:
# tools/tools.txt, the one list of the tools.
BAKE_LIST := $(shell awk '!/^\#/ && NF && $$2 != "-" {print $$1 ":" $$2}' \
  $(dir $(BAKE_MK))tools/tools.txt)
BAKE_TOOLS := $(foreach step,$(BAKE_LIST),$(word 1,$(subst :, ,$(step))))
BAKE_OUTPUTS := $(foreach step,$(BAKE_LIST),$(word 2,$(subst :, ,$(step))))

.PHONY: bake bake-force slurm-bake
bake:
bake-force:

# make slurm-bake SCENE=... SHARDS=N: the same bake submitted to Slurm
# (tools/slurm_bake.sh), photons and cluster as job arrays of N shards. The stamps are
# made here first, so that the jobs only run the tools.
slurm-bake: $(foreach s,scene-hash images-hash $(BAKE_TOOLS:%=%-flags),$(BAKE)/$(SCENE_NAME).$(s))
	BAKE_MK=$(BAKE_MK) BIN=$(abspath $(BIN)) BAKE=$(BAKE) SCENE=$(SCENE) SHARDS=$(SHARDS) \
	  VOXELIZE_FLAGS='$(VOXELIZE_FLAGS)' THIN_FLAGS='$(THIN_FLAGS)' \
	  SEGMENT_FLAGS='$(SEGMENT_FLAGS)' PHOTONS_FLAGS='$(PHOTONS_FLAGS)' \
	  CLUSTER_FLAGS='$(CLUSTER_FLAGS)' ATLAS_FLAGS='$(ATLAS_FLAGS)' \
	  LIGHTMAP_FLAGS='$(LIGHTMAP_FLAGS)' PREFIX=$(BAKE)/$(SCENE_NAME) \
	  sh $(dir $(BAKE_MK))tools/slurm_bake.sh

# timed PREFIX,TOOL: GNU time into PREFIX.TOOL.time, with TIME_BAKE=1.
timed = $(if $(TIME_BAKE),/usr/bin/time -f '%e %U %S %M' -o $(1).$(2).time)

# write_if_changed TEXT,FILE: FILE gets the line TEXT, or keeps its time when
# it has it already; through a temporary of its own and a rename, so that
# several makes at once (make -j, Slurm tasks) never see a part. mktemp
# makes the temporary 0600; chmod =rw gives it 0666 less the umask, as the
# tools' own outputs have.
write_if_changed = t=$$(mktemp $(2).XXXXXX) && chmod =rw $$t && printf '%s\n' '$(1)' >$$t && \
  { cmp -s $$t $(2) && rm -f $$t || mv $$t $(2); }

# bake_scene SCENE,PREFIX: the rules of one scene's bake into PREFIX.*.
define bake_scene
$(if $(filter $(2),$(BAKE_PREFIXES)),$(error two scenes named $(notdir $(2)) in SCENES: \
  bake them into different BAKE folders))
BAKE_PREFIXES += $(2)
$(if $(wildcard $(2).source),$(if $(filter-out $(abspath $(1)),$(file <$(2).source)),\
  $(error $(2).*: baked from $(file <$(2).source); $(1) has the same name: give it \
  another BAKE folder, or remove $(2).*)))
bake: $(addprefix $(2),$(BAKE_OUTPUTS))

$(2).content: $(1) $(BIN)/scene-info
	@mkdir -p $$(@D)
	$(BIN)/scene-info --quiet --hash $$@ --depfile $$@.d $(1)
	@echo $(abspath $(1)) >$(2).source
-include $(2).content.d

$(2).scene-hash: $(2).content
	@$$(call write_if_changed,$$(shell grep '^scene_hash ' $$<),$$@)
$(2).images-hash: $(2).content
	@$$(call write_if_changed,$$(shell grep '^images_hash ' $$<),$$@)
$(foreach tool,$(BAKE_TOOLS),
$(2).$(tool)-flags: bake-force
	@mkdir -p $$(@D); $$(call write_if_changed,$($(call flags_of,$(tool))),$$@)
)
$(2).vdb: $(2).scene-hash $(2).voxelize-flags $(BIN)/voxelize
	$(call timed,$(2),voxelize) $(BIN)/voxelize $(VOXELIZE_FLAGS) $(1) -o $$@

# thin writes both the skeleton and the nearest-node grid (a grouped target).
$(2).skel $(2).grid.vdb &: $(2).vdb $(2).thin-flags $(BIN)/thin
	$(call timed,$(2),thin) $(BIN)/thin $(THIN_FLAGS) $(2).vdb -o $(2).skel \
	  --grid $(2).grid.vdb

# segment fits the gates to the voxels' openings (--voxels, --grid): the
# gates the runtime draws.
$(2).seg: $(2).skel $(2).vdb $(2).grid.vdb $(2).segment-flags $(BIN)/segment
	$(call timed,$(2),segment) $(BIN)/segment $(SEGMENT_FLAGS) $(2).skel \
	  --voxels $(2).vdb --grid $(2).grid.vdb -o $$@

ifeq ($(SHARDS),1)
$(2).phot: $(2).scene-hash $(2).images-hash $(2).photons-flags $(BIN)/photons
	$(call timed,$(2),photons) $(BIN)/photons $(PHOTONS_FLAGS) $(1) -o $$@
else
# SHARDS=N: the photons in N independent parts (photons --shard I/N), merged
# into the bytes of the whole run (photons --merge).
$(foreach i,$(shard_indices),
$(2).phot.$(i)-of-$(SHARDS): $(2).scene-hash $(2).images-hash $(2).photons-flags $(BIN)/photons
	$(BIN)/photons $(PHOTONS_FLAGS) --shard $(i)/$(SHARDS) $(1) -o $$@
)
$(2).phot: $(foreach i,$(shard_indices),$(2).phot.$(i)-of-$(SHARDS)) $(BIN)/photons
	$(call timed,$(2),photons) $(BIN)/photons --merge $$(filter %-of-$(SHARDS),$$^) -o $$@
endif

ifeq ($(SHARDS),1)
$(2).lot: $(2).scene-hash $(2).phot $(2).cluster-flags $(BIN)/cluster
	$(call timed,$(2),cluster) $(BIN)/cluster $(CLUSTER_FLAGS) $(1) $(2).phot -o $$@
else
# SHARDS=N: the octree's leaves in N ranges (cluster --shard I/N, each
# indexing the photons its leaves can reach), merged into the bytes of the
# whole run.
$(foreach i,$(shard_indices),
$(2).lot.$(i)-of-$(SHARDS): $(2).scene-hash $(2).phot $(2).cluster-flags $(BIN)/cluster
	$(BIN)/cluster $(CLUSTER_FLAGS) --shard $(i)/$(SHARDS) $(1) $(2).phot -o $$@
)
$(2).lot: $(foreach i,$(shard_indices),$(2).lot.$(i)-of-$(SHARDS)) $(BIN)/cluster
	$(call timed,$(2),cluster) $(BIN)/cluster --merge $$(filter %-of-$(SHARDS),$$^) -o $$@
endif

$(2).atlas: $(2).scene-hash $(2).atlas-flags $(BIN)/atlas
	$(call timed,$(2),atlas) $(BIN)/atlas $(ATLAS_FLAGS) $(1) -o $$@

# lightmap bakes the octree into the atlas (OUT.exr) and exports the scene
# with it (OUT.glb, which embeds the scene's images: hence images-hash).
$(2).lightmap.exr $(2).glb &: $(2).scene-hash $(2).images-hash $(2).atlas $(2).lot \
  $(2).lightmap-flags $(BIN)/lightmap
	$(call timed,$(2),lightmap) $(BIN)/lightmap $(LIGHTMAP_FLAGS) $(1) $(2).atlas $(2).lot \
	  -o $(2).lightmap.exr --glb $(2).glb
endef

# flags_of TOOL: the name of its flags variable, e.g. VOXELIZE_FLAGS.
flags_of = $(subst voxelize,VOXELIZE,$(subst thin,THIN,$(subst segment,SEGMENT,$(subst \
  photons,PHOTONS,$(subst cluster,CLUSTER,$(subst atlas,ATLAS,$(subst \
  lightmap,LIGHTMAP,$(1))))))))_FLAGS

$(foreach scene,$(SCENES),$(eval $(call bake_scene,$(scene),$(BAKE)/$(basename \
  $(notdir $(scene))))))
