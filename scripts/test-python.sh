#!/usr/bin/env bash
# Builds the Python package as `pip install ./python` does (maturin, release), installs it into
# the project's test environment (target/python-env, made by scripts/setup.sh) and runs pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
PY_ENV=target/python-env
if [ ! -x "$PY_ENV/bin/python" ]; then
  echo "no $PY_ENV: run scripts/setup.sh first" >&2
  exit 1
fi
# --force-reinstall --no-deps: the package itself, rebuilt from this tree, not a cached wheel.
"$PY_ENV/bin/pip" install -q --force-reinstall --no-deps ./python
# Outside the repository, so `import logic_lfd` is the installed wheel, not python/logic_lfd.
cd target
"../$PY_ENV/bin/python" -m pytest -q -p no:cacheprovider ../python/tests "$@"
