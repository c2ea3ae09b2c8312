# Быстрый старт: `make report` (собирает отчёт по варианту по умолчанию), `make test` (все тесты).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
CASE   ?= cases/ws000_six_bar_corrected.toml

.PHONY: report test setup bench bench-precision clean

report: setup
	$(BIN)/reportgen build $(CASE)

test: setup
	$(BIN)/python -m pytest

bench: setup
	$(BIN)/python bench/bench_cli.py

# время против погрешности (кинематика, аналоги-пакеты в output/bench/peer-venv, динамика, разделы)
bench-precision: setup
	$(BIN)/python bench/work_precision.py --peers

setup: $(VENV)/.installed

$(VENV)/.installed: pyproject.toml scripts/setup.sh
	PYTHON=$(PYTHON) bash scripts/setup.sh
	touch $@

clean:
	rm -rf $(VENV) output .pytest_cache
