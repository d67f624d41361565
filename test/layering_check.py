#!/usr/bin/python3
"""Holds the components' arrows one way (README's "Layout").

Every component sits on a level; a component's files (library, tools and tests alike) may include
and link only components on lower levels, never one on its own level or above. Checked twice:
  - includes: `#include "COMPONENT/..."` in any C++ file under a component's folder;
  - CMake: every target named in a component's target_link_libraries, mapped to the component
    that defines it, and every include folder a component's CMakeLists.txt adds from another
    component (a reach into another component's tools/ or src/ is an arrow too).
Prints each arrow that breaks the order, with its file and line, and exits 1 if there is one.

  layering_check.py [SOURCE_DIR]
  layering_check.py --self-test     shows that it finds arrows up and sideways in a made-up tree
"""
import pathlib
import re
import sys
import tempfile

# Level of each component folder: the bottom first. Siblings on one level do not see each other.
LEVELS = {
    "tool_args": 0,       # command-line parsing and charts for the tools
    "package_data": 0,    # finds the package's share folder at run time
    "bench_support": 1,   # what the benches of several components share
    "grid": 2,            # maps, line of sight, the input checks everyone shares
    "nava_modem": 2,      # the audio link: modem profiles, framing, MAC, audio I/O
    "ranging": 2,         # two-way acoustic ranging from timings of packets
    "behaviours": 3,      # reactive robot behaviours (the wanderer)
    "world_sim": 4,       # the simulated world
    "local_navigation": 5,  # driving with no global map (and world_sim's readings for it)
    "audio_propagation": 5,  # sound paths and the simulated audio channel
    "local_mutex": 6,     # the lock the tasks share chargers and places with
    "sounds_good_explorer": 7,  # the tasks
    "charging_demo": 7,
    "src": 8,             # the ROS nodes and bridges
    "test": 9,            # the rostests
    "fuzz": 9,            # the fuzz targets
}

SOURCES = (".h", ".hpp", ".cpp", ".cc")
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([A-Za-z_]+)/')
TARGET_DEF = re.compile(r'^\s*add_(?:library|executable)\(\s*([A-Za-z0-9_]+)', re.M)
# The ROS side's gtests and rostests (declared in cmake/ros.cmake) are test/'s.
TEST_DEF = re.compile(r'^\s*(?:add_rostest_gtest|catkin_add_gtest)\(\s*([A-Za-z0-9_]+)', re.M)
LINKS = re.compile(r'target_link_libraries\(\s*([A-Za-z0-9_$<>{}:.]+)([^)]*)\)', re.S)
INCLUDE_DIRS = re.compile(r'target_include_directories\(([^)]*)\)', re.S)


def component_of(path, root):
    parts = path.relative_to(root).parts
    return parts[0] if parts and parts[0] in LEVELS else None


def cmake_files(root):
    for name in LEVELS:
        folder = root / name
        if (folder / "CMakeLists.txt").exists():
            yield name, folder / "CMakeLists.txt"
    # The ROS side's targets live in cmake/ros.cmake; they belong to src/ (and test/).
    yield "src", root / "cmake" / "ros.cmake"


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def check(root):
    problems = []

    def arrow(where, line, source, target, what):
        if target == source or target not in LEVELS or source not in LEVELS:
            return
        if LEVELS[target] >= LEVELS[source]:
            problems.append(f"{where}:{line}: {source} (level {LEVELS[source]}) {what} {target} "
                            f"(level {LEVELS[target]}): components use only those below them")

    for path in sorted(root.rglob("*")):
        if path.suffix not in SOURCES or not path.is_file():
            continue
        if any(part.startswith("build") or part in ("devel", ".git") for part in path.relative_to(root).parts):
            continue
        source = component_of(path, root)
        if source is None:
            continue
        for number, text in enumerate(path.read_text(errors="replace").splitlines(), 1):
            match = INCLUDE.match(text)
            if match:
                arrow(path.relative_to(root), number, source, match.group(1), "includes")

    owner = {}
    texts = {}
    for name, cmake in cmake_files(root):
        if not cmake.exists():
            continue
        texts[cmake] = (name, cmake.read_text())
        for match in TARGET_DEF.finditer(texts[cmake][1]):
            owner[match.group(1)] = name
        for match in TEST_DEF.finditer(texts[cmake][1]):
            owner[match.group(1)] = "test"
    for cmake, (name, text) in texts.items():
        for match in LINKS.finditer(text):
            linker = owner.get(match.group(1), name)
            for word in match.group(2).split():
                if word in owner:
                    arrow(cmake.relative_to(root), line_of(text, match.start()), linker, owner[word], "links")
        for match in INCLUDE_DIRS.finditer(text):
            words = match.group(1).split()
            if not words or words[0].startswith("${"):
                continue  # a target a CMake function names by a variable: its own callers say whose
            user = owner.get(words[0], name)
            for folder in re.findall(r'\$\{PROJECT_SOURCE_DIR\}/([A-Za-z_]+)', match.group(1)):
                arrow(cmake.relative_to(root), line_of(text, match.start()), user, folder, "adds the include folder of")
    return problems


def self_test():
    """A tree with one arrow of each kind that breaks the order, and one that does not."""
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        files = {
            "grid/src/a.cpp": '#include "grid/a.h"\n#include "world_sim/world.h"\n',
            "world_sim/src/b.cpp": '#include "grid/a.h"\n',
            "charging_demo/src/c.cpp": '#include "sounds_good_explorer/x.h"\n',
            "grid/CMakeLists.txt": "add_library(grid a.cpp)\ntarget_link_libraries(grid PUBLIC world_sim)\n",
            "world_sim/CMakeLists.txt": "add_library(world_sim b.cpp)\ntarget_link_libraries(world_sim PUBLIC grid)\n",
            "nava_modem/CMakeLists.txt": ("add_executable(t t.cpp)\n"
                                          "target_include_directories(t PRIVATE ${PROJECT_SOURCE_DIR}/audio_propagation/tools)\n"),
        }
        for name, text in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        found = "\n".join(check(root))
        expected = ["grid/src/a.cpp:2: grid (level 2) includes world_sim",
                    "charging_demo/src/c.cpp:1: charging_demo (level 7) includes sounds_good_explorer",
                    "grid/CMakeLists.txt:2: grid (level 2) links world_sim",
                    "nava_modem/CMakeLists.txt:2: nava_modem (level 2) adds the include folder of audio_propagation"]
        missing = [e for e in expected if e not in found]
        extra = len(found.splitlines()) - len(expected)
        if missing or extra:
            print(f"layering_check --self-test: missing {missing}, {extra} unexpected, found:\n{found}")
            return 1
    print("layering_check --self-test: every arrow against the order found, none other")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    unknown = [p.name for p in root.iterdir()
               if p.is_dir() and (p / "CMakeLists.txt").exists() and p.name not in LEVELS]
    if unknown:
        print(f"layering_check: components with no level: {', '.join(sorted(unknown))}; "
              f"give each a level in {__file__}")
        return 1
    problems = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"layering_check: {len(problems)} arrows against the order")
        return 1
    print(f"layering_check: {len(LEVELS)} components, every include and link points down")
    return 0


if __name__ == "__main__":
    sys.exit(main())
