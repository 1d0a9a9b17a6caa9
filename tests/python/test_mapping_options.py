"""The mapping options come from one table in the library (mapping/mapping_option_table.hpp):
the stub's keyword block is what the table renders, and every keyword is accepted by
map_sonar_log, OnlineMapper and detect_obstacles with the library's default (tests/cli's
test_cli_options.cpp checks the flags and help of `sonarmap map` and `sonarmap live`).

Run as a script with --write (PYTHONPATH=build/python) to rewrite the stub's block from the table:
    PYTHONPATH=build/python /usr/bin/python3 tests/python/test_mapping_options.py --write
"""

import pathlib
import sys

import pytest

import sonarmap

STUB = pathlib.Path(__file__).resolve().parents[2] / "python" / "sonarmap" / "__init__.pyi"
BEGIN = "# BEGIN mapping options\n"
END = "# END mapping options\n"


def stub_block(options):
    """The stub's lines between BEGIN and END: a TypedDict of every keyword with its type."""
    lines = ["class _MappingOptions(TypedDict, total=False):\n"]
    lines += [f"    {option['keyword']}: {option['type']}\n" for option in options]
    return "".join(lines)


def stub_parts(text):
    """The stub's text before the block, the block, and after it."""
    start = text.index(BEGIN) + len(BEGIN)
    end = text.index(END, start)
    return text[:start], text[start:end], text[end:]


def test_stub_keywords_are_the_tables():
    before, block, after = stub_parts(STUB.read_text())
    expected = stub_block(sonarmap.mapping_options())
    assert block == expected, (
        "python/sonarmap/__init__.pyi differs from the mapping option table; rewrite it with\n"
        "    PYTHONPATH=build/python /usr/bin/python3 tests/python/test_mapping_options.py --write\n"
        f"expected block:\n{expected}"
    )


def test_every_keyword_is_accepted_with_the_librarys_default(simulated_tank, tmp_path):
    options = sonarmap.mapping_options()
    defaults = {option["keyword"]: option["default"] for option in options}
    sonarmap.map_sonar_log(simulated_tank.log, **defaults).write(str(tmp_path / "given.bt"))
    sonarmap.map_sonar_log(simulated_tank.log).write(str(tmp_path / "default.bt"))
    assert (tmp_path / "given.bt").read_bytes() == (tmp_path / "default.bt").read_bytes()
    sonarmap.OnlineMapper(**defaults)
    detection = {option["keyword"]: option["default"] for option in options if option["stage"] == "detection"}
    polar = sonarmap.polar_image(simulated_tank.log)
    assert sonarmap.detect_obstacles(polar, **detection)["obstacle_bin"].tolist() == \
        sonarmap.detect_obstacles(polar)["obstacle_bin"].tolist()


def test_every_word_is_accepted_and_a_bad_one_names_the_keyword(simulated_tank):
    polar = sonarmap.polar_image(simulated_tank.log)
    for option in sonarmap.mapping_options():
        if not option["words"] or option["stage"] != "detection":
            continue
        for word in option["words"]:
            sonarmap.detect_obstacles(polar, **{option["keyword"]: word})
        with pytest.raises(sonarmap.ValueError, match=f"^{option['keyword']} expects"):
            sonarmap.detect_obstacles(polar, **{option["keyword"]: "bogus"})


if __name__ == "__main__":
    if sys.argv[1:] != ["--write"]:
        sys.exit(__doc__)
    head, _, tail = stub_parts(STUB.read_text())
    STUB.write_text(head + stub_block(sonarmap.mapping_options()) + tail)
    print(f"rewrote the mapping options of {STUB}")
