# Быстрый старт: `make report` (собирает отчёт по варианту по умолчанию), `make test` (все тесты).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
CASE   ?= cases/ws000_six_bar_corrected.toml

.PHONY: report test setup setup-test bench bench-precision clean

report: setup
	$(BIN)/reportgen build $(CASE)

test: setup-test
	$(BIN)/python -m pytest

# все цифры issue #15 (bench/results/cli.json, docs/performance.md); около 10 минут на 2 ядрах
bench: setup
	$(BIN)/python bench/bench_cli.py

# время против погрешности (кинематика, аналоги-пакеты в output/bench/peer-venv, динамика, разделы)
bench-precision: setup-test
	$(BIN)/python bench/work_precision.py --peers

setup: $(VENV)/.installed

setup-test: $(VENV)/.installed-test

$(VENV)/.installed: pyproject.toml scripts/setup.sh
	PYTHON=$(PYTHON) bash scripts/setup.sh
	touch $@

$(VENV)/.installed-test: $(VENV)/.installed
	PYTHON=$(PYTHON) bash scripts/setup.sh --test
	touch $@

clean:
	rm -rf $(VENV) output .pytest_cache
