#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Formatting check (CI): every tracked C++ file must be as Debian's clang-format formats it with
# the repository's .clang-format. Fix with: git ls-files -z '*.cpp' '*.hpp' | xargs -0 clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files -z '*.cpp' '*.hpp' '*.h' '*.cc' | xargs -0 clang-format --dry-run -Werror
echo "check-format: $(git ls-files '*.cpp' '*.hpp' '*.h' '*.cc' | wc -l) files formatted"
