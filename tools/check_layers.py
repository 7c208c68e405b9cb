#!/usr/bin/env python3
"""check_layers.py SRC_DIR — the module layering of src/, checked by reading the #include lines.

Rules (docs/theory.md §2, src/CMakeLists.txt):
  * core includes only core, and names no contactor, interaction, law or solver: the 5-letter
    names live with their modules (contactors/contactor_kind.*, interactions/contact_table.hpp,
    laws/law_table.hpp, solvers/solver_kind.hpp).
  * the registry includes only table headers (data: *_table.hpp, round_tables.hpp, and the kinds,
    parameters and material pairs they need), and those include only core and each other: the
    registry that gathers them is plain data.
  * each module includes only itself, the modules below it, and the registry (which brings every
    table, not the functions of the modules above).
  * VTK headers appear only in io; SuiteSparse headers only in solvers/newton_ac.cpp.
Prints every violation and exits 1 if there is one.
"""
import pathlib
import re
import sys

BELOW = {
    "core": set(),
    "registry": {"core", "bodies", "contactors", "interactions", "laws"},  # table headers only
    "laws": {"core", "registry"},
    "bodies": {"core", "registry", "laws"},
    "contactors": {"core", "registry", "laws", "bodies"},
    "interactions": {"core", "registry", "laws", "bodies", "contactors"},
    "solvers": {"core", "registry", "laws", "bodies", "contactors", "interactions"},
    "io": {"core", "registry", "laws", "bodies", "contactors", "interactions"},
}
NAMES = re.compile(r"\b(POLYG|DISKx|JONCx|xKSID|PT2Dx|PLPLx|PTPT2|DKDKx|DKPLx|DKJCx|PLJCx|DKKDx|"
                   r"IQS_CLB|RST_CLB|GAP_SGR_CLB|VOIGT_ROD|NLGS|NEWTON_AC|Polyg|Diskx|Joncx|Xksid)\b")
INCLUDE = re.compile(r'#include\s+"nscd/([a-z_]+)/([A-Za-z0-9_.]+)"')
SYSTEM = re.compile(r"#include\s+<([^>]+)>")


def registry_headers(src):
    """The headers registry/registry.hpp includes: the modules' table headers."""
    text = (src / "registry" / "registry.hpp").read_text()
    return {(m.group(1), m.group(2)) for m in INCLUDE.finditer(text)}


def main(src):
    errors = []
    tables = registry_headers(src)
    for (dep, header) in sorted(tables):
        if dep != "core" and not (header.endswith("_table.hpp") or header == "round_tables.hpp" or
                                  header in ("contactor_kind.hpp", "material_pairs.hpp")):
            errors.append(f"{src}/registry/registry.hpp: includes nscd/{dep}/{header}, not a table header")
    for path in sorted(src.glob("*/*.[hc]pp")):
        module, name = path.parent.name, path.name
        if module not in BELOW:
            errors.append(f"{path}: unknown module folder '{module}' (add it to tools/check_layers.py)")
            continue
        text = path.read_text()
        for m in INCLUDE.finditer(text):
            dep, header = m.group(1), m.group(2)
            if dep == module:
                continue
            if dep not in BELOW[module]:
                errors.append(f"{path}: includes nscd/{dep}/{header}, above {module}")
        if (module, name) in tables:
            for m in INCLUDE.finditer(text):
                if m.group(1) != "core" and (m.group(1), m.group(2)) not in tables:
                    errors.append(f"{path}: a table header includes nscd/{m.group(1)}/{m.group(2)}, not a table header")
        if module == "core":
            code = re.sub(r"//[^\n]*", "", text)  # comments may mention the vocabulary
            for m in NAMES.finditer(code):
                errors.append(f"{path}: core names '{m.group(1)}'")
        for m in SYSTEM.finditer(text):
            h = m.group(1)
            if h.startswith("vtk") and module != "io":
                errors.append(f"{path}: VTK header <{h}> outside io")
            if re.match(r"(suitesparse/)?(klu|umfpack|cholmod|amd|colamd|SuiteSparse_config)\.h", h) \
                    and path.relative_to(src).as_posix() != "solvers/newton_ac.cpp":
                errors.append(f"{path}: SuiteSparse header <{h}> outside solvers/newton_ac.cpp")
    for e in errors:
        print(e)
    print(f"check_layers: {len(errors)} violation(s) in {src}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "src")))
