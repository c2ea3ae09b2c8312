#!/usr/bin/env bash
# Установка всего, что нужно проекту, на чистой машине (Debian + Python ≥ 3.11):
# системные пакеты (шрифты Liberation Serif и osifont, poppler-utils), виртуальное окружение .venv,
# пакет reportgen с зависимостями для тестов и прогрев кэша numba.
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON=${PYTHON:-python3}

need_apt=()
[ -f /usr/share/fonts/truetype/liberation2/LiberationSerif-Regular.ttf ] || need_apt+=(fonts-liberation2)
command -v pdftotext >/dev/null 2>&1 || need_apt+=(poppler-utils)
# lettering of the A1 drawing sheets: osifont (ISO 3098, the construction of ГОСТ 2.304 type B)
[ -f /usr/share/fonts/truetype/osifont/osifont.ttf ] || need_apt+=(fonts-osifont)
if [ ${#need_apt[@]} -gt 0 ]; then
  if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
    echo "reportgen: установка системных пакетов: ${need_apt[*]}" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq "${need_apt[@]}" >/dev/null
  else
    echo "reportgen: нет прав на apt-get; будут использованы шрифты из matplotlib (${need_apt[*]} не установлены)" >&2
  fi
fi

if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip >/dev/null
.venv/bin/python -m pip install -q -e ".[test]"
# компиляция ядер numba один раз (cache=True), чтобы первый отчёт строился за секунды
.venv/bin/reportgen warmup
