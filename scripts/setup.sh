#!/usr/bin/env bash
# Установка всего, что нужно проекту, на чистой машине (Debian + Python ≥ 3.11):
# системные пакеты (шрифты Liberation Serif и osifont, poppler-utils, HarfBuzz-Subset),
# виртуальное окружение .venv, пакет reportgen с зависимостями (только колёса, без сборки
# из исходников) и прогрев кэшей (ядра numba, список шрифтов matplotlib), чтобы первый
# отчёт строился не дольше повторного.
#   scripts/setup.sh          — для отчётов (`make report`)
#   scripts/setup.sh --test   — ещё и зависимости тестов (`make test`, CI)
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON=${PYTHON:-python3}
# --no-compile: no bytecode written at install for the whole of scipy, pandas, matplotlib… (≈ 20 s of CPU);
# Python writes it on first import for the modules actually used (≈ 6 s, in `reportgen warmup` below)
PIP=(.venv/bin/python -m pip install -q --disable-pip-version-check --only-binary=:all: --no-compile)

if [ "${1:-}" = "--test" ]; then
  # test extras only (the runtime is installed by the plain run, which `make test` runs first)
  "${PIP[@]}" -e ".[test]"
  exit 0
fi

need_apt=()
[ -f /usr/share/fonts/truetype/liberation2/LiberationSerif-Regular.ttf ] || need_apt+=(fonts-liberation2)
command -v pdftotext >/dev/null 2>&1 || need_apt+=(poppler-utils)
# lettering of the A1 drawing sheets: osifont (ISO 3098, the construction of ГОСТ 2.304 type B)
[ -f /usr/share/fonts/truetype/osifont/osifont.ttf ] || need_apt+=(fonts-osifont)
# font subsets of the PDF by HarfBuzz (WeasyPrint falls back to fontTools, several times slower)
{ /sbin/ldconfig -p 2>/dev/null || ldconfig -p 2>/dev/null || true; } | grep -q 'libharfbuzz-subset\.so\.0' \
  || need_apt+=(libharfbuzz-subset0)
if [ ${#need_apt[@]} -gt 0 ]; then
  if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
    echo "reportgen: установка системных пакетов: ${need_apt[*]}" >&2
    export DEBIAN_FRONTEND=noninteractive
    # the package lists are read again only when apt cannot find a package
    apt-get install -y -qq --no-install-recommends "${need_apt[@]}" >/dev/null 2>&1 \
      || { apt-get update -qq >/dev/null && apt-get install -y -qq --no-install-recommends "${need_apt[@]}" >/dev/null; }
  else
    echo "reportgen: нет прав на apt-get; не установлены: ${need_apt[*]} (шрифты будут взяты из matplotlib)" >&2
  fi
fi

if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
# wheels only (no compiler, no source builds); pip as it comes with the venv
"${PIP[@]}" -e .
# numba kernels compiled once (cache=True), matplotlib's font list built, the report's fonts
# registered: the first report is built with warm caches
.venv/bin/reportgen warmup
