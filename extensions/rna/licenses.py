"""Licenses a package can choose: SPDX id, LICENSE file text, and per-file header.

The headers are the notices ament_copyright recognises for each license, so the
generated packages pass `ament_copyright` (part of ament_lint_common).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

_TEXTS = Path(__file__).resolve().parent.parent / "licenses"

_APACHE_NOTICE = """\
Licensed under the Apache License, Version 2.0 (the "License");
you may not use this file except in compliance with the License.
You may obtain a copy of the License at

    http://www.apache.org/licenses/LICENSE-2.0

Unless required by applicable law or agreed to in writing, software
distributed under the License is distributed on an "AS IS" BASIS,
WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
See the License for the specific language governing permissions and
limitations under the License."""

_GNU_NOTICE = """\
This program is free software: you can redistribute it and/or modify
it under the terms of the GNU {lesser}General Public License as published by
the Free Software Foundation, either version 3 of the License, or
(at your option) any later version.

This program is distributed in the hope that it will be useful,
but WITHOUT ANY WARRANTY; without even the implied warranty of
MERCHANTABILITY or FITNESS FOR A PARTICULAR PURPOSE.  See the
GNU {lesser}General Public License for more details.

You should have received a copy of the GNU {lesser}General Public License
along with this program.  If not, see <https://www.gnu.org/licenses/>."""


@dataclass(frozen=True)
class License:
    spdx: str
    title: str
    notice: str

    def text(self, copyright_line: str) -> str:
        """The LICENSE file."""
        text = (_TEXTS / f"{self.spdx}.txt").read_text()  # not through rna/files.py: the template's license texts
        return text.replace("{copyright}", copyright_line)

    def header(self, copyright_line: str, comment: str) -> str:
        """The comment block that starts every source file (`comment` is '#' or '//')."""
        lines = [copyright_line, "", *self.notice.splitlines()]
        return "\n".join(f"{comment} {line}".rstrip() for line in lines)


LICENSES = {
    license.spdx: license
    for license in (
        License("Apache-2.0", "Apache License 2.0", _APACHE_NOTICE),
        License("BSD-3-Clause", "BSD 3-Clause License",
                "Use of this source code is governed by a BSD-style\n"
                "license that can be found in the LICENSE file or at\n"
                "https://developers.google.com/open-source/licenses/bsd"),
        License("MIT", "MIT License",
                "Use of this source code is governed by an MIT-style\n"
                "license that can be found in the LICENSE file or at\n"
                "https://opensource.org/licenses/MIT."),
        License("GPL-3.0-or-later", "GNU General Public License v3.0 or later",
                _GNU_NOTICE.format(lesser="")),
        License("LGPL-3.0-or-later", "GNU Lesser General Public License v3.0 or later",
                _GNU_NOTICE.format(lesser="Lesser ")),
    )
}


def get_license(spdx: object) -> License:
    try:
        return LICENSES[spdx]
    except (KeyError, TypeError):
        raise ValueError(f"'{spdx}' is not one of {', '.join(LICENSES)}") from None
