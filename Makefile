# The README's two commands are `make run` and `make test`; the rest are their parts.
SHELL := /bin/bash
VENV := .venv
PY := $(VENV)/bin/python
PORT ?= 8000
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: surface-model coco-detector picodet-detector detector-model suggester-detector-model scratch-detector-model bench-detector bench-refine bench-batch completion-model box-refiner-model mesh-net-model scene-net-model bench-completion bench-writers calibrate-scale bench bench-layout bench-depth-layout bench-box-parts bench-synth bench-geometry bench-support bench-relation vectors relation-vectors detector-vectors decode-vectors class-vectors test-frontend run test install install-python install-node install-chromium install-postgres build schema schema-check \
        lint format pytest e2e demo serve clean

run: install build demo serve

test: install install-chromium install-postgres schema-check lint pytest test-frontend build e2e

install: install-python install-node

install-python: $(VENV)/.installed
$(VENV)/.installed: pyproject.toml
	test -x $(PY) || python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev,train]"
	touch $@

install-node: node_modules/.package-lock.json
node_modules/.package-lock.json: package.json package-lock.json frontend/package.json e2e_tests/package.json shared_schema/package.json
	npm install --no-audit --no-fund
	touch $@

# Browser tests use Debian's Chromium; never a test tool's own browser download.
install-chromium:
	@command -v chromium >/dev/null || { $(SUDO) apt-get update -qq && $(SUDO) apt-get install -y -qq chromium; }

# The store tests also run on a scratch PostgreSQL server (docs/database.md): Debian's package.
install-postgres:
	@ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 || { $(SUDO) apt-get update -qq && $(SUDO) apt-get install -y -qq postgresql; }

build: install-node
	npm run build

schema:
	$(PY) -m holiscene_schema.export
	npm run generate

schema-check:
	$(PY) -m holiscene_schema.export --check
	npm run -s -w shared_schema check

lint:
	$(VENV)/bin/ruff check backend shared_schema benchmarks scripts
	$(VENV)/bin/ruff format --check backend shared_schema benchmarks scripts
	$(VENV)/bin/mypy
	$(VENV)/bin/mypy benchmarks scripts
	npm run -s lint

format:
	$(VENV)/bin/ruff check --fix backend shared_schema benchmarks scripts
	$(VENV)/bin/ruff format backend shared_schema benchmarks scripts
	npm run -s format

# Without PostgreSQL the store tests' PostgreSQL runs would only be skipped: here they must run.
pytest:
	HOLISCENE_REQUIRE_POSTGRES=1 $(VENV)/bin/pytest -q

e2e:
	cd e2e_tests && ../node_modules/.bin/playwright test

demo:
	$(VENV)/bin/holiscene demo

serve:
	$(VENV)/bin/holiscene serve --port $(PORT)

clean:
	rm -rf $(VENV) node_modules frontend/dist var

bench: install-python
	$(PY) benchmarks/bench_infer.py

bench-synth: install-python
	$(PY) benchmarks/bench_synth.py

bench-support: install-python
	$(PY) benchmarks/bench_support.py --seed 900000 --count 200

bench-relation: install-python
	$(PY) benchmarks/bench_relation.py

bench-geometry: install-python
	$(PY) benchmarks/bench_synth.py --seed 7000 --count 20
	$(PY) benchmarks/bench_placement.py

# Where the layout IoU goes: each part of the layout stage against the truth.
bench-layout: install-python
	$(PY) benchmarks/bench_layout_parts.py --seed 7000 --count 20 --plot docs/img/layout_parts.png

bench-depth-layout: install-python
	OMP_NUM_THREADS=1 $(PY) benchmarks/bench_layout_parts.py --depth --seed 310000 --count 150

# Where the single-photo 3D boxes lose (issue 23): each part of the boxes made true in turn.
bench-box-parts: install-python
	$(PY) benchmarks/bench_box_parts.py --seed 950000 --count 10 --per-class

# The learned parts of the layout stage, both from synthetic rooms (commit what they write):
# the Surface Network (floor/ceiling/wall labels) and the per-class metric-scale calibration.
# Build time only: npm fetches @vladmandic/human and TensorFlow.js into a scratch folder; the
# COCO detector is converted to ONNX and checked against TensorFlow.js on the real photos.
coco-detector: install-python
	$(PY) scripts/convert_coco_detector.py

# The default detector: COCO PicoDet from its PyPI package, converted and checked against Paddle.
picodet-detector: install-python
	$(PY) scripts/convert_picodet_detector.py

# The NYU-40 detector: a head fine-tuned on synthetic rooms over the COCO backbone.
detector-model: install-python
	rm -rf /tmp/holiscene-detector-model
	$(PY) -m holiscene.cli train-detector -o /tmp/holiscene-detector-model --scenes 1000 --views 2 --epochs 20 --tune-deep-blocks
	cp /tmp/holiscene-detector-model/* backend/src/holiscene/learning/nyu_detector/

# For comparison only: a small CenterNet with no pretrained weights, trained on the same rooms
# on two CPU threads; training stops, annealed, after 25 minutes (docs/detector.md).
# The scene page's suggester (docs/detector.md): PicoDet's boxes named with NYU-40 classes by a
# head trained on synthetic rooms; it does not name books itself (half its real-photo boxes).
suggester-detector-model: install-python
	rm -rf /tmp/holiscene-suggester-detector
	$(PY) -m holiscene.cli train-detector --on-picodet -o /tmp/holiscene-suggester-detector \
		--scenes 1000 --views 2 --epochs 12 --unnamed books
	mkdir -p backend/src/holiscene/learning/picodet_nyu_detector
	cp /tmp/holiscene-suggester-detector/* backend/src/holiscene/learning/picodet_detector/LICENSE \
		backend/src/holiscene/learning/picodet_nyu_detector/

scratch-detector-model: install-python
	rm -rf /tmp/holiscene-scratch-detector
	mkdir -p backend/src/holiscene/learning/scratch_detector
	$(PY) -m holiscene.cli train-detector --from-scratch -o /tmp/holiscene-scratch-detector \
		--scenes 1000 --epochs 16 --time-budget 1500
	cp /tmp/holiscene-scratch-detector/* backend/src/holiscene/learning/scratch_detector/

bench-detector: install-python
	$(PY) benchmarks/bench_detector.py --model backend/src/holiscene/learning/picodet_detector \
		--model backend/src/holiscene/learning/coco_detector \
		--model backend/src/holiscene/learning/nyu_detector \
		--model backend/src/holiscene/learning/scratch_detector

# Save latency with 20 annotators at once, on SQLite and on a scratch PostgreSQL (docs/database.md).
bench-writers: install-python install-postgres
	$(PY) benchmarks/bench_writers.py

# The mask tools' refine call (GrabCut steered by strokes) on 400x400 boxes of the real photos.
bench-refine: install-python
	$(PY) benchmarks/bench_refine.py

# Photos per minute pre-annotated on a local Ray (1 and 2 workers) against the in-process import.
bench-batch: install-python
	$(PY) benchmarks/bench_batch.py

# Shape completion: the network trained on partial scans of the furniture library for 18
# minutes on one thread (docs/completion.md), and its comparison with the library fit.
completion-model: install-python
	rm -rf /tmp/holiscene-completion-model
	OMP_NUM_THREADS=1 $(PY) -m holiscene.cli train-completion -o /tmp/holiscene-completion-model
	cp /tmp/holiscene-completion-model/* backend/src/holiscene/learning/completion_model/

box-refiner-model: install-python
	rm -rf /tmp/holiscene-box-refiner-model
	OMP_NUM_THREADS=1 $(PY) -m holiscene.cli train-3d box-refiner -o /tmp/holiscene-box-refiner-model
	cp /tmp/holiscene-box-refiner-model/* backend/src/holiscene/learning/box_refiner_model/

# The mesh network: 25 minutes on the 2 cores (docs/mesh-net.md).
mesh-net-model: install-python
	rm -rf /tmp/holiscene-mesh-net-model
	$(PY) -m holiscene.cli train-3d meshes -o /tmp/holiscene-mesh-net-model
	cp /tmp/holiscene-mesh-net-model/* backend/src/holiscene/learning/mesh_net_model/

scene-net-model: install-python
	rm -rf /tmp/holiscene-scene-net-model
	$(PY) -m holiscene.cli train-3d scene-net -o /tmp/holiscene-scene-net-model --cache /tmp/holiscene-scene-net-cache
	cp /tmp/holiscene-scene-net-model/* backend/src/holiscene/learning/scene_net_model/

bench-completion: install-python
	OMP_NUM_THREADS=1 $(PY) benchmarks/bench_completion.py

surface-model: install-python
	rm -rf /tmp/holiscene-surface-model
	$(PY) -m holiscene.cli train-surfaces -o /tmp/holiscene-surface-model --scenes 6000 --epochs 30
	cp /tmp/holiscene-surface-model/* backend/src/holiscene/learning/default_surface_model/

calibrate-scale: install-python
	$(PY) scripts/calibrate_scale.py

# The room-fit and object-colour test vectors shared by the Python and TypeScript tests.
vectors:
	$(PY) -m holiscene.twin_vectors.room_fit
	$(PY) -m holiscene.twin_vectors.object_colours

# The Relation Network's vectors (preprocessing + the default model's logits) shared by the
# backend and the browser; run after changing the default model or the preprocessing.
relation-vectors:
	$(PY) -m holiscene.twin_vectors.relation_model

# The object detector's vectors (preprocessing, the default detector's raw rows, decoding)
# shared by the backend and the browser; run after changing the default detector, its
# preprocessing or its decoding.
detector-vectors:
	$(PY) -m holiscene.twin_vectors.detector_model
	$(PY) -m holiscene.twin_vectors.detector_model \
		--model-dir backend/src/holiscene/learning/picodet_nyu_detector \
		-o shared_schema/vectors/suggester_model.json

# The support-tree decoder's vectors (Python decode.py <-> frontend/src/inference/treeDecode.ts).
decode-vectors:
	$(PY) -m holiscene.twin_vectors.support_decode

# Class names keyed and stored alike (holiscene_schema/classes.py <-> frontend/src/state/classNames.ts).
class-vectors:
	$(PY) -m holiscene.twin_vectors.class_names

test-frontend: install-node
	npm run -s -w frontend test
