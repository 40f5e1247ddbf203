# SPSC toolchain. First use creates .venv and installs the project into it.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp

# our files hold Δ, ³, –: never let a POSIX locale make Python's default encoding ASCII
export PYTHONUTF8 := 1

TYPE     ?= D
MATERIAL ?= tpu60a
QUICK    ?=
# optional geometry overrides: make bladder TYPE=D W=11 H=13 L=3 T0=1 N1=2 N2=2.2 CY=0.6
GEOM_ARGS = $(if $(W),--w $(W)) $(if $(H),--h $(H)) $(if $(L),--l $(L)) $(if $(T0),--t0 $(T0)) \
            $(if $(N1),--n1 $(N1)) $(if $(N2),--n2 $(N2)) $(if $(CY),--cy $(CY))

.PHONY: help venv bladder mold fingertip fingertip-fem haptic-fem time-study gate test test-slow test-long test-all docs bench bench-mold bench-compare bench-wall bench-speed bench-material bench-sweep bench-time bench-sense bench-hysteresis bench-friction bench-gap bench-surrogate surrogate-check surrogate-check-table1 durability-study clean

help:
	@echo "make bladder TYPE=A|B|C|D [W= H= L= T0= N1= N2= CY= MATERIAL=]  -> build/bladder-TYPE/"
	@echo "    (with overrides: build/bladder-TYPE-NAME=VALUE.../, e.g. W=12 -> build/bladder-D-w=12/)"
	@echo "make bladder TYPE=D HAPTIC=1    (the haptic chamber, FIT0774 motor) -> build/bladder-D-haptic/"
	@echo "make mold TYPE=A|B|C|D [PROCESS=casting|compression] [W= ...]  -> build/mold-TYPE/"
	@echo "    (likewise: PROCESS=compression -> build/mold-TYPE-process=compression/)"
	@echo "make fingertip                                                   -> build/fingertip/"
	@echo "make fingertip-fem [FT_MESH=2]                                 -> build/fingertip/fem/"
	@echo "make haptic-fem                                                -> build/haptic-fem/ (the motor's cost)"
	@echo "make time-study                                                -> build/time-study/ (trace, Bode, hysteresis)"
	@echo "make test | make test-slow | make test-long | make test-all | make docs | make gate | make bench | make report [QUICK=1]"

# the install takes about 3.5 GB (VTK, MKL, OpenCASCADE, CasADi); pip unpacks into a folder on
# the venv's own disk (not a /tmp that may be a small RAM disk) and keeps no wheel cache
PIP_TMP := $(CURDIR)/$(VENV)/.pip-tmp
PIP     := TMPDIR=$(PIP_TMP) $(BIN)/python -m pip install --quiet --no-cache-dir
$(STAMP): pyproject.toml
	@echo "installing into $(VENV): about 4 GB needed, $$(df -Pk . | awk 'NR==2 {printf "%.1f", $$4/1048576}') GB free here"
	$(PYTHON) -m venv $(VENV)
	mkdir -p $(PIP_TMP)
	$(PIP) --upgrade pip
	$(PIP) -e ".[test,docs,sim]"
	# tests/spsc_support (what tests and benchmarks share) on the environment's path, outside
	# the installed package
	$(BIN)/python -c "import pathlib, site; pathlib.Path(site.getsitepackages()[0], 'spsc-tests.pth').write_text('$(CURDIR)/tests\n')"
	rm -rf $(PIP_TMP)
	touch $(STAMP)

venv: $(STAMP)

HAPTIC ?=
bladder: $(STAMP)
	$(BIN)/spsc bladder --type $(TYPE) --material $(MATERIAL) $(GEOM_ARGS) $(if $(HAPTIC),--haptic)

# the mold of the bladder's wall: pieces (STL, 3MF, STEP), mold.json, the mold gate, a render
PROCESS ?= casting
mold: $(STAMP)
	$(BIN)/spsc mold --type $(TYPE) --process $(PROCESS) $(GEOM_ARGS)

fingertip: $(STAMP)
	$(BIN)/spsc fingertip

# the fingertip in the 3D FEM: pulp and distal presses, both modes, 10 and 40 kPa, pocket forces,
# the single chamber and the fast estimate (build/fingertip/fem/; hours on 2 cores, curves reused)
FT_MESH ?= 2
fingertip-fem: $(STAMP)
	$(BIN)/spsc fingertip --fem --mesh-size $(FT_MESH) --out build/fingertip

# the haptic chamber's cost: Type D, the haptic chamber without and with its motor (part FEM,
# three curves, 10–15 min; reused when they exist)
haptic-fem: $(STAMP)
	$(BIN)/spsc haptic --out build/haptic-fem

# the chamber in time for the report: the press-hold-switch trace, its Bode plot, the
# squeeze-release hysteresis of Types A-D (about 3 min); spsc report shows build/time-study
time-study: $(STAMP)
	$(BIN)/spsc simulate examples/press-hold-switch.toml --study --out build/time-study --cache build/cache

# the printability gate on every preset and the mold gate on every type (run by CI)
gate: $(STAMP)
	@set -e; for t in A B C D; do $(MAKE) --no-print-directory bladder TYPE=$$t; done
	@$(MAKE) --no-print-directory fingertip
	@$(MAKE) --no-print-directory bladder TYPE=D HAPTIC=1
	@set -e; for t in A B C D; do $(BIN)/spsc mold --type $$t --no-render; done
	@$(BIN)/spsc mold --type B --process compression --no-render --out build/mold-B-compression

# the fast suite on every core (pytest-xdist), progress as a count, the slowest five at the end;
# a module's tests stay on one worker (--dist loadscope), so a module-scoped fixture (a built
# bladder, a meshed chamber) is built once, not once per worker
PYTEST = $(BIN)/python -m pytest -q -n auto --dist loadscope --durations=5
test: $(STAMP)
	$(PYTEST)

# the slow CAD/FEM/report cases only (@pytest.mark.slow) but the longest: CI runs make test, then
# this; test by test over the workers (--dist load: the three report tests of minutes each on one
# worker took 905 s against 845-873 s)
test-slow: $(STAMP)
	$(PYTEST) --dist load -m "slow and not long"

# the longest slow cases (@pytest.mark.long, minutes each), which CI leaves out for time
test-long: $(STAMP)
	$(PYTEST) -m long

# everything in one run: the fast suite and the slow cases
test-all: $(STAMP)
	$(PYTEST) -m ""

# the documentation site (MkDocs, API reference from the docstrings) into build/site
docs: $(STAMP)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --quiet

# quick benchmarks (minutes); bench-compare runs the FEM-vs-models tables (about 30 min)
bench: $(STAMP)
	@set -e; for f in bench_cad bench_membrane bench_fem bench_gate_broken; do \
	  echo "== bench/$$f.py"; $(BIN)/python bench/$$f.py; done
	@echo "== bench/bench_wall.py speed (wall vs membrane; the 3D FEM figure is bench_fem's)"
	@$(BIN)/python bench/bench_wall.py speed --type B
	@$(BIN)/python bench/bench_wall.py speed --type B --dome

# the molds of A-D: time of make mold, volume identities, pull tests, broken molds (issue 15)
bench-mold: $(STAMP)
	$(BIN)/python bench/bench_mold.py

# material fitting and calibration figures (issue 12; about 6 min)
bench-material: $(STAMP)
	$(BIN)/python bench/bench_material.py

# issue 26's interactive-speed figures that take minutes (wall and 3D FEM curves, the CLI's
# start-up; about 3 min), with the commands of the longer rows
bench-speed: $(STAMP)
	$(BIN)/python bench/bench_speed.py

# the wall model against the 3D FEM (references: about 40 min the first time, then cached)
bench-wall: $(STAMP)
	$(BIN)/python bench/fem_reference.py
	$(BIN)/python bench/bench_wall.py errors
	$(BIN)/python bench/bench_wall.py wrinkling
	$(BIN)/python bench/bench_wall.py convergence --type B --dome
	$(BIN)/python bench/bench_wall.py convergence --type B

bench-time: $(STAMP)
	$(BIN)/python bench/bench_time.py

# the chamber as a sensor (issue 29): 200 generated scenarios on Types A-D, then the haptic
# loop on a Type D squeeze (about 4 min; the chamber maps are built once into build/cache)
bench-sense: $(STAMP)
	$(BIN)/python bench/bench_sense.py
	$(BIN)/python bench/bench_haptic.py

# the bench gap factor by factor (wall model, about 90 min, 75 of them the Coulomb rows),
# shown by make report; MATERIAL_ROW=FIT.json adds the row of your material fit
bench-gap: $(STAMP)
	$(BIN)/spsc bench-gap --out build/bench-gap $(if $(MATERIAL_ROW),--material-row $(MATERIAL_ROW))

# the shipped surrogate against the wall model on 200 fresh domes (about a minute), shown
# by make report; bench-surrogate: its speed (quiet machine)
surrogate-check: $(STAMP)
	$(BIN)/spsc surrogate check --samples 200 --out build/surrogate-check
# the shipped surrogate of Table 1's stadiums on 64 fresh ones (about 6 minutes on 2 cores)
surrogate-check-table1: $(STAMP)
	$(BIN)/spsc surrogate check table1 --samples 64 --out build/surrogate-check-table1
# the paper's fatigue and puncture tests in the wall model (15-20 minutes), shown by make report
durability-study: $(STAMP)
	$(BIN)/spsc fatigue --study --out build/durability

bench-surrogate: $(STAMP)
	$(BIN)/python bench/bench_surrogate.py $(if $(FULL),--sweep --design)

# the plate's friction: increments, work, wall against 3D FEM, the Table 1 means with
# mu = 0, 0.3, 0.6 and stick (the Coulomb curves are slow: about an hour on 2 cores)
bench-friction: $(STAMP)
	mkdir -p build/bench
	$(BIN)/python bench/bench_friction.py --json build/bench/friction.json

bench-hysteresis: $(STAMP)
	$(BIN)/python bench/bench_hysteresis.py

bench-compare: $(STAMP)
	$(BIN)/python bench/bench_fem_compare.py

# spsc sweep on Dask: designs/s with 1 and 2 workers, memory at 25/50/100 % (MEMBRANE=1000
# WALL=200 by default, about 25 min + 3 h on an idle 2-core machine; MEMBRANE=100 WALL=8 to check)
MEMBRANE ?= 1000
WALL     ?= 200
bench-sweep: $(STAMP)
	$(BIN)/python bench/bench_sweep.py --membrane $(MEMBRANE) --wall $(WALL)

# validation report: reports/validation/index.html; QUICK=1 -> build/report-quick/ (CI)
.PHONY: report
report: $(STAMP)
	$(BIN)/spsc report $(if $(QUICK),--quick)

clean:
	rm -rf build .pytest_cache .hypothesis
