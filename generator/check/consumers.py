"""Independent consumers of a URDF: urdfdom's check_urdf, pinocchio, yourdfpy and (when installed) MuJoCo.

Each runs in its own process with a time limit and an output cap, so a consumer that crashes, hangs or prints forever
(check_urdf does on a cycle that hangs off the root) is reported, never propagated; one that refuses the URDF is a C001
finding. Run as ``python -m xacrokit.check.consumers NAME FILE`` this module loads FILE with one Python consumer and
prints one JSON line (it imports little, and the package ``xacrokit.check`` loads its modules only when asked).
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..expansion.bounded_child import Bounds, ChildFailed, OutOfBounds, start_bounded
from ..shared.ros_packages import find_package
from .consumer_host import ConsumerHost, one_line
from .findings import ConsumerResult, Finding, rule_table, severity

if TYPE_CHECKING:
    from .consumer_host import ConsumerHost
    from .urdf_document import Doc

RULES = rule_table(
    {
        "C001": (
            "consumer-accepts",
            "error",
            "an independent consumer loads the URDF (MuJoCo judges it without the .dae, .glb and ASCII STL meshes "
            "it cannot read, a limit of its own, and says how many it left out)",
        )
    }
)

CONSUMERS = ("check_urdf", "pinocchio", "yourdfpy", "mujoco")
SHARING = ("yourdfpy",)  # consumers that import what check's rules may read meshes with (trimesh, scipy.spatial)
LIBRARIES = {"pinocchio": "pinocchio", "yourdfpy": "yourdfpy", "mujoco": "mujoco"}  # consumer -> its Python module
TIMEOUT_S = 30.0
OUTPUT_CAP = 64 * 1024  # bytes of a consumer's output kept at its start, and at its end
HARD_CAP = 64 * 1024 * 1024  # bytes: a consumer printing more is stopped (check_urdf loops printing on a rooted cycle)


def chosen(names: Sequence[str] | None) -> list[str]:
    """The consumers to run: by default every installed one; those asked for by name must exist and be installed (a
    verdict that was asked for is never left out)."""
    if names is None:
        return [n for n in CONSUMERS if available(n)]
    unknown = [n for n in names if n not in CONSUMERS]
    if unknown:
        raise XacrokitError(f"unknown consumer(s) {', '.join(unknown)}; choose from {', '.join(CONSUMERS)}")
    missing = [n for n in names if not available(n)]
    if missing:
        hint = " (pip install mujoco)" if "mujoco" in missing else ""
        raise XacrokitError(
            f"consumer(s) {', '.join(missing)} asked for but not installed{hint}; install them, or leave them out "
            "of --consumers"
        )
    return list(names)


def available(name: str) -> bool:
    if name == "check_urdf":
        return _check_urdf_binary() is not None
    return importlib.util.find_spec(LIBRARIES[name]) is not None


def _check_urdf_binary() -> str | None:
    return shutil.which("check_urdf", path=str(Path(sys.executable).parent)) or shutil.which("check_urdf")


def check_urdf_command(program: str) -> tuple[list[str], dict[str, str] | None]:
    """How to start urdfdom's check_urdf found at ``program``, and its environment (None: this process's). The pin
    wheel installs a launcher, cmeel's, that starts Python to run the program in its ``cmeel.prefix`` with that
    prefix's libraries: 55 ms a file, where the program itself takes 2. So the launcher's program is run as the
    launcher would run it (its ``bin/`` program, its ``lib/`` first in LD_LIBRARY_PATH)."""
    try:
        with open(program, "rb") as head:
            launcher = b"cmeel_run" in head.read(512)
        # (heavy: cmeel)
        from cmeel.consts import CMEEL_PREFIX  # type: ignore[import-untyped]

        # (heavy: cmeel)
        from cmeel.run import __file__ as cmeel_run  # type: ignore[import-untyped]
    except (OSError, ImportError):
        return [program], None
    prefix = Path(cmeel_run).parent.parent / CMEEL_PREFIX
    binary = prefix / "bin" / Path(program).name
    if not launcher or not os.access(binary, os.X_OK):
        return [program], None
    libraries = os.environ.get("LD_LIBRARY_PATH")
    environment = {**os.environ, "LD_LIBRARY_PATH": f"{prefix / 'lib'}" + (f":{libraries}" if libraries else "")}
    return [str(binary)], environment


def _run_capped(
    command: list[str], timeout: float, cwd: Path | None = None, env: dict[str, str] | None = None
) -> tuple[int | None, str, bool]:
    """Run ``command``; return (exit code or None on timeout, its output, overflowed). The output kept is the first and
    the last OUTPUT_CAP bytes with every line that starts with ``Error:`` in between (check_urdf prints a big robot's
    whole tree: its length is no verdict); a consumer still printing after HARD_CAP bytes is stopped (overflowed)."""
    process = subprocess.Popen(
        command,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        stdin=subprocess.DEVNULL,
        cwd=cwd,
        env=env,
        start_new_session=True,  # its own process group: stopping it stops what it started too
    )

    def stop() -> None:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(process.pid, signal.SIGKILL)  # (a child left behind would hold the pipe open)

    head: list[bytes] = []
    tail = bytearray()
    errors: list[bytes] = []
    overflow = threading.Event()

    def drain() -> None:
        size, carry = 0, b""
        stream = process.stdout
        assert stream is not None  # (stdout=PIPE)
        for chunk in iter(lambda: stream.read(65536), b""):
            if size < OUTPUT_CAP:
                head.append(chunk)
            else:
                tail.extend(chunk)
                del tail[: max(0, len(tail) - OUTPUT_CAP)]
                *lines, carry = (carry + chunk).split(b"\n")
                errors.extend(line for line in lines if line.lstrip().startswith(b"Error:"))
                del errors[20:]
            size += len(chunk)
            if size > HARD_CAP:
                overflow.set()
                stop()  # a consumer printing without end: its verdict is already clear
                break

    reader = threading.Thread(target=drain, daemon=True)
    reader.start()
    try:
        code: int | None = process.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        stop()
        process.wait()
        code = None
    except BaseException:  # (Ctrl-C: the consumer, in a session of its own, did not get it)
        stop()
        raise
    stop()  # what the consumer started and left running (it would hold the output pipe open)
    reader.join(timeout=5)
    kept = b"".join(head) + (b"\n" + b"\n".join(errors) + b"\n" + bytes(tail) if tail else b"")
    return (None if overflow.is_set() else code), kept.decode("utf-8", errors="replace"), overflow.is_set()


def _tail(text: str, lines: int = 3) -> str:
    kept = [_without_sources(line) for line in text.strip().splitlines() if not _AT_SOURCE.match(line)]
    return " | ".join([line for line in kept if line][-lines:])


# urdfdom reports through console_bridge: "Error:   MESSAGE" and, on the next line, "at line N in FILE", FILE the path
# of urdfdom's own C++ source where it was built (/project/urdfdom/urdf_parser/src/joint.cpp, /home/...): the place in
# urdfdom's code, which says nothing of the robot and much of the machine that built it. A build may say its place as
# FILE:LINE in the message instead (an exception's text).
_AT_SOURCE = re.compile(r"^\s*at line \d+ in \S+\s*$")
_SOURCE_PLACE = re.compile(
    r"(?:[ \t]*\bat line \d+ in )?(?:[A-Za-z]:)?(?:[^\s:'\"\[\]()]*[/\\])+[^\s:'\"\[\]()/\\]+"
    r"\.(?:c|cc|cpp|cxx|h|hh|hpp|hxx)\b(?::\d+)*:?"
)


_NAMED = re.compile(r"(\[[^\]]*\]|'[^']*')")  # (a name as urdfdom quotes it: [shoulder], 'arm')


def _without_sources(text: str) -> str:
    """``text`` without the places in urdfdom's (or any C++) source code it names (outside the names it quotes, which
    stay as written), runs of spaces made one."""
    parts = _NAMED.split(text)
    parts[::2] = [re.sub(r"[ \t]{2,}", " ", _SOURCE_PLACE.sub("", part)) for part in parts[::2]]
    return "".join(parts).strip()


def _urdfdom_errors(text: str, most: int = 3) -> str:
    """urdfdom's own error messages, first first (the first says what is wrong; the rest say where it gave up),
    without the places in urdfdom's code that follow each. A message goes on to that place: a name with a line break
    in it (``Joint [a\\nb]``) is kept whole."""
    errors: list[list[str]] = []
    going_on: list[str] = []  # (lines after an Error: line, its message's until a place in urdfdom's code ends it)
    for line in text.split("\n"):
        if line.lstrip().startswith("Error:"):
            errors.append([line.lstrip()[len("Error:") :].strip()])
            going_on = []
        elif _AT_SOURCE.match(line) and errors:
            errors[-1] += going_on
            going_on = []
        elif errors:
            going_on.append(line)
    said = [_without_sources("\n".join(parts)) for parts in errors]
    return " | ".join([message for message in said if message][:most])


def run_consumer(
    name: str,
    urdf_path: Path,
    timeout: float = TIMEOUT_S,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> ConsumerResult:
    if not available(name):
        return ConsumerResult(
            name, "unavailable", "not installed" + (" (pip install mujoco)" if name == "mujoco" else "")
        )
    environment = None
    if name == "check_urdf":
        program, environment = check_urdf_command(_check_urdf_binary() or "check_urdf")
        command = [*program, str(urdf_path.resolve())]
    else:
        packages = json.dumps({k: str(v) for k, v in (package_paths or {}).items()})
        command = [sys.executable, "-m", "xacrokit.check.consumers", name, str(urdf_path.resolve()), packages]
    # in the URDF's own folder: consumers may leave files behind (MuJoCo writes MUJOCO_LOG.TXT where it runs)
    code, output, overflow = _run_capped(command, timeout, cwd=urdf_path.resolve().parent, env=environment)
    if overflow:
        return ConsumerResult(name, "rejected", f"printed more than {HARD_CAP:,} bytes without ending; stopped")
    if code is None:
        return ConsumerResult(name, "timeout", f"no verdict within {timeout:g} s; stopped")
    if name == "check_urdf":
        if code == 0 and "Successfully Parsed XML" in output and not _urdfdom_errors(output):
            return ConsumerResult(name, "accepted")  # (urdfdom prints some errors, such as an unreadable rpy, and
            # goes on to exit 0: an error line is a rejection all the same)
        return ConsumerResult(name, "rejected", _urdfdom_errors(output) or _tail(output) or f"exit code {code}")
    try:
        verdict = json.loads(output.strip().splitlines()[-1])
    except (ValueError, IndexError):
        return ConsumerResult(name, "crashed", _tail(output) or f"exit code {code}")
    return ConsumerResult(name, verdict["status"], verdict.get("message", ""))


def _started(
    names: list[str],
    urdf_path: Path,
    timeout: float = TIMEOUT_S,
    package_paths: Mapping[str, str | os.PathLike[str]] | None = None,
) -> Callable[[], list[ConsumerResult]]:
    """Start the named consumers side by side (a thread each, waiting on its process); the function returned waits
    for them and gives their results in the order asked."""
    results: dict[str, ConsumerResult] = {}

    def run(name: str) -> None:
        results[name] = run_consumer(name, urdf_path, timeout, package_paths)

    threads = [threading.Thread(target=run, args=(n,)) for n in names]
    for thread in threads:
        thread.start()

    def collect() -> list[ConsumerResult]:
        for thread in threads:
            thread.join()
        return [results[n] for n in names]

    return collect


def verdicts(
    names: list[str],
    text: str,
    *,
    structural: bool,
    package_paths: Mapping[str, str | os.PathLike[str]] | None,
    base_dir: Path,
) -> list[ConsumerResult]:
    """The named consumers' verdicts on a URDF text checked as the file in ``base_dir``; skipped when the structure is
    broken (``structural``)."""
    if structural:
        return skipped(names)
    return start_verdicts(names, text, package_paths=package_paths, base_dir=base_dir)()


def skipped(names: list[str]) -> list[ConsumerResult]:
    """The named consumers, not run on a URDF whose structure is broken: a tree that is not a tree hangs check_urdf
    and crashes others, and our finding says it all."""
    return [ConsumerResult(n, "skipped", "not run: the structure errors above make the URDF unusable") for n in names]


def start_verdicts(
    names: list[str],
    text: str,
    *,
    package_paths: Mapping[str, str | os.PathLike[str]] | None,
    base_dir: Path,
    shown_as: str = "the URDF",
    prepare: Callable[[], None] | None = None,
) -> Callable[[], list[ConsumerResult]]:
    """:func:`verdicts`, started (on a URDF whose structure is sound: :func:`skipped` otherwise): the consumers run
    while the caller goes on (check runs its other rules meanwhile), and the function returned waits for their
    verdicts (``shown_as``: how their messages name the file). ``prepare``: what the caller loads that the consumers
    of SHARING load too (check's mesh readers: trimesh, which yourdfpy imports), called once the others are started
    and before those are forked, which inherit it."""
    if not names:
        return list
    folder = tempfile.TemporaryDirectory(prefix="xacrokit-check-")
    try:
        urdf = _scratch_copy(text, base_dir, Path(folder.name))
        # the Python consumers in children forked from this process, which has numpy and lxml loaded already (a
        # process of their own would start Python and import them again: a third of the time it takes); started
        # before the thread that runs check_urdf (a fork copies one thread only)
        forkable = hasattr(os, "fork")  # (elsewhere each runs as a process of its own, as check_urdf does)
        python = [n for n in names if forkable and n != "check_urdf" and available(n)]
        if _HOST and prepare is not None:
            prepare()  # (the host, started once, inherits it)
        hosted = [_HOST[0].start(python, urdf, package_paths)] if _HOST and python else []
        # (warm: those whose child started with the check, its library imported meanwhile: sent the URDF now)
        hosted += [_WARM[n].start([n], urdf, package_paths) for n in python if n in _WARM and not _HOST]
        each = [n for n in python if n not in _WARM and not _HOST]  # (a child forked now for each)
        # the consumers that share nothing with the caller start first, on the other core, while it prepares
        forked = {n: _forked(n, urdf, package_paths) for n in each if n not in SHARING}
        if not _HOST and prepare is not None and any(n in SHARING for n in each):
            prepare()
        forked |= {n: _forked(n, urdf, package_paths) for n in each if n in SHARING}
        others = _started([n for n in names if n not in python], urdf, package_paths=package_paths)
    except BaseException:
        folder.cleanup()
        raise

    def collect() -> list[ConsumerResult]:
        try:
            results = {name: wait() for name, wait in forked.items()}
            for wait in hosted:
                results.update(wait())
            results.update((r.name, r) for r in others())
            # (a message naming the scratch copy names the file checked: a verdict does not depend on where it ran)
            return [replace(results[n], message=results[n].message.replace(str(urdf), shown_as)) for n in names]
        finally:
            folder.cleanup()

    return collect


def _scratch_copy(text: str, base_dir: Path, folder: Path) -> Path:
    """The URDF ``text`` written as ``folder``/robot.urdf, its relative mesh paths (relative to the checked file, in
    ``base_dir``) made absolute first, so that they still lead to the meshes from there."""
    from lxml import etree  # (here, not at the top: this module is also each Python consumer's process)

    root = _read(text.encode("utf-8"))
    for mesh in root.iter("mesh"):
        filename = mesh.get("filename", "")
        if filename and "://" not in filename and not Path(filename).is_absolute():
            mesh.set("filename", str(base_dir.resolve() / filename))
    urdf = folder / "robot.urdf"
    urdf.write_text(etree.tostring(root, encoding="unicode"), encoding="utf-8")
    return urdf


_HOST: list[ConsumerHost] = []  # (the host the Python consumers run in, while :func:`hosted_consumers` holds one)
_WARM: dict[str, ConsumerHost] = {}  # (a host per Python consumer, started early, while :func:`warm_consumers` lasts)
YIELDING = {"pinocchio": 10}  # consumer -> how much its warm child yields the CPU (a load of a few hundredths)


@contextlib.contextmanager
def warm_consumers(names: Sequence[str]) -> Iterator[None]:
    """While it lasts, the next check in this process sends each of the Python consumers ``names`` to a child of its
    own started now (:class:`~xacrokit.check.consumer_host.ConsumerHost`, the bounds of a forked consumer's), which
    imports the consumer's library at once: the slowest consumer's import (yourdfpy's, a second) then runs while
    check reads the file and runs its first rules, instead of after. numpy, which every one of them imports, is
    imported here first and shared; a consumer that loads in a few hundredths (pinocchio) yields the CPU to the
    others (YIELDING). Nothing is started where there is no fork, or while :func:`hosted_consumers` holds a host."""
    forkable = hasattr(os, "fork") and not _HOST
    wanted = [n for n in names if n in LIBRARIES and n not in _WARM and available(n)] if forkable else []
    if wanted:
        import numpy  # noqa: F401  (heavy: numpy; imported before the children start, which share it)
    hosts = {n: ConsumerHost(load_with, CONSUMER_BOUNDS, LIBRARIES[n], YIELDING.get(n, 0)) for n in wanted}
    try:
        for host in hosts.values():
            host.warm_up()
        _WARM.update(hosts)
        yield
    finally:
        for name, host in hosts.items():
            _WARM.pop(name, None)
            host.stop()


@contextlib.contextmanager
def hosted_consumers() -> Iterator[None]:
    """While it lasts, every check in this process runs its Python consumers in one long-lived child
    (:mod:`xacrokit.check.consumer_host`: what MuJoCo has compiled is kept for the next robot) instead of a child per
    consumer and file."""

    host = ConsumerHost(load_with, CONSUMER_BOUNDS)
    _HOST[:] = [host]
    try:
        yield
    finally:
        _HOST.clear()
        host.stop()


CONSUMER_BOUNDS = Bounds(seconds=TIMEOUT_S, memory=4 * 2**30, output=64 * 1024)


def _forked(
    name: str, urdf: Path, package_paths: Mapping[str, str | os.PathLike[str]] | None
) -> Callable[[], ConsumerResult]:
    """Start one Python consumer on ``urdf`` in a forked child (quiet, bounded in time, memory and output: a consumer
    that crashes, hangs or floods takes only its child with it); the function returned waits for its verdict."""
    packages = {k: str(v) for k, v in (package_paths or {}).items()}

    def work() -> str:
        os.chdir(urdf.parent)  # (MuJoCo writes MUJOCO_LOG.TXT where it runs: into the scratch folder)
        return load_with(name, str(urdf), packages)

    def described(exc: BaseException) -> dict[str, str] | None:
        return {"message": one_line(exc)} if isinstance(exc, Exception) else None

    wait = start_bounded(work, CONSUMER_BOUNDS, errors=described, quiet=True)

    def verdict() -> ConsumerResult:
        try:
            text, error = wait()
        except OutOfBounds as exc:
            if exc.which == "seconds":
                return ConsumerResult(name, "timeout", f"no verdict within {exc.bounds.seconds:g} s; stopped")
            return ConsumerResult(name, "rejected", f"went past its {exc.which} bound; stopped")
        except ChildFailed as exc:
            return ConsumerResult(name, "crashed", exc.detail)
        if error is not None:
            return ConsumerResult(name, "rejected", str(error["message"]))
        return ConsumerResult(name, "accepted", text or "")

    return verdict


def _read(data: bytes) -> Any:
    """The root element of a URDF our rules have read: leniently, as those rules do, for undeclared namespace prefixes
    (U003), which consumers read past; the elements stay as written."""
    from lxml import etree  # (heavy: lxml)

    from ..shared.xml_parse import parser  # (heavy: lxml)

    return etree.fromstring(data, parser(recover=True))


def consumer_findings(results: Sequence[ConsumerResult], file: str, doc: Doc | None = None) -> list[Finding]:
    """C001: a finding for each consumer that refused the URDF, crashed on it or gave no verdict in time; placed (given
    the ``doc`` checked) at the link or joint its message names, where the document has one of that name."""
    found = []
    for r in results:
        if not r.failed:
            continue
        message = f"{r.name} {r.status}: {r.message}".rstrip(": ")
        element = _named_element(r.message, doc) if doc is not None else None
        if doc is not None and element is not None:
            found.append(doc.finding("C001", "consumer", r.name, message, element))
        else:
            found.append(Finding("C001", severity("C001"), "consumer", r.name, message, file))
    return found


# How consumers name the element they stopped at: urdfdom "Joint [elbow] is of type ...", "Could not parse visual
# element for Link [arm]", "link 'arm' is not unique.", "child link [ghost] of joint [elbow] not found"; MuJoCo
# "Element name 'arm', id 2" (a body is named after its link, a joint after its joint).
_NAMES = re.compile(r"\b(link|joint)\s*(?:\[([^\]]*)\]|'([^']*)')|\bElement name '([^']*)'", re.IGNORECASE)


def _named_element(message: str, doc: Doc) -> Any:
    """The first link or joint of ``doc`` that ``message`` names (for a name given twice, 'not unique', the second
    element of that name: the one that repeats it); None when it names none the document has."""
    for match in _NAMES.finditer(message):
        kind, name = (match.group(1) or "").lower(), match.group(2) or match.group(3) or match.group(4) or ""
        kinds = [kind] if kind else ["link", "joint"]
        for each in kinds:
            parts = doc.view.links if each == "link" else doc.view.joints
            elements = [part.element for part in parts if part.name == name]
            if elements:
                repeated = "not unique" in message[match.end() : match.end() + 20]
                return elements[-1] if repeated else elements[0]
    return None


def load_with(name: str, path: str, packages: Mapping[str, str] | None = None) -> str:
    """Load the URDF with one library; return a one-line description of what it saw."""
    if name == "pinocchio":
        import pinocchio  # (heavy: pinocchio)

        model = pinocchio.buildModelFromUrdf(path)
        return f"{model.njoints - 1} joints, {model.nframes} frames"
    if name == "yourdfpy":
        import yourdfpy  # (heavy: yourdfpy)

        robot = yourdfpy.URDF.load(path, build_scene_graph=True, load_meshes=False, load_collision_meshes=False)
        return f"{len(robot.link_map)} links, {len(robot.joint_map)} joints"
    import mujoco  # (heavy: mujoco)

    # MuJoCo opens mesh files by plain path: hand it the files that package:// and file:// URIs name. It cannot read
    # some formats (.dae, .glb, ASCII STL): a limit of MuJoCo, not a defect of the file, so the visuals and collisions
    # made of them are left out and MuJoCo judges the rest (the bodies, their inertia, the joints)
    text, left_out = _without_meshes_mujoco_cannot_read(_with_mesh_paths(path, packages or {}))
    model = mujoco.MjModel.from_xml_string(text)
    return f"{model.nbody} bodies" + (f" ({left_out} left out: MuJoCo cannot read them)" if left_out else "")


MUJOCO_MESH_FORMATS = (".stl", ".obj", ".msh")  # MuJoCo 3-4's mesh readers (binary STL only)


def _without_meshes_mujoco_cannot_read(urdf: str) -> tuple[str, str]:
    """``urdf`` without the visuals and collisions whose mesh file MuJoCo cannot read, and what was left out
    ('3 .dae and 1 ASCII STL meshes'; '' when nothing was)."""
    from lxml import etree  # (heavy: lxml)

    root = _read(urdf.encode("utf-8"))
    formats: dict[str, int] = {}
    for mesh in list(root.iter("mesh")):
        name = mesh.get("filename", "")
        suffix = Path(name).suffix.lower()
        unreadable = (suffix or "suffix-less") if suffix not in MUJOCO_MESH_FORMATS else ""
        if suffix == ".stl" and _ascii_stl(Path(name)):
            unreadable = "ASCII STL"
        shape = next((a for a in mesh.iterancestors() if a.tag in ("visual", "collision")), None)
        if unreadable and shape is not None and shape.getparent() is not None:
            formats[unreadable] = formats.get(unreadable, 0) + 1
            shape.getparent().remove(shape)
    said = " and ".join(f"{n} {what}" for what, n in formats.items())
    if said:
        said += " meshes" if sum(formats.values()) > 1 else " mesh"
    return etree.tostring(root, encoding="unicode"), said


def _ascii_stl(path: Path) -> bool:
    """An STL in the ASCII form (MuJoCo reads the binary one only): it starts with 'solid' and its size is not that of
    a binary STL (84 bytes and 50 per triangle, the count at byte 80)."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(84)
        size = path.stat().st_size
    except OSError:
        return False  # (a missing file: MuJoCo's own complaint, and R003's)
    if not head.startswith(b"solid") or len(head) < 84:
        return head.startswith(b"solid")
    return size != 84 + 50 * int.from_bytes(head[80:84], "little")


def _with_mesh_paths(path: str, packages: Mapping[str, str]) -> str:
    from lxml import etree  # (heavy: lxml)

    root = _read(Path(path).read_bytes())
    for mesh in root.iter("mesh"):
        filename = mesh.get("filename", "")
        if filename.startswith("package://"):
            package, _, rest = filename[len("package://") :].partition("/")
            try:
                mesh.set("filename", str(Path(find_package(package, packages)) / rest))
            except LookupError:
                pass  # left as written: MuJoCo's own complaint is the verdict
        elif filename.startswith("file://"):
            mesh.set("filename", filename[len("file://") :])
    return etree.tostring(root, encoding="unicode")


def main(argv: list[str] | None = None) -> int:
    words = argv if argv is not None else sys.argv[1:]
    name, path = words[:2]
    packages = json.loads(words[2]) if len(words) > 2 else {}
    try:
        seen = load_with(name, path, packages)
        print(json.dumps({"status": "accepted", "message": seen}))
    except Exception as exc:  # a consumer's own complaint is its verdict
        print(json.dumps({"status": "rejected", "message": one_line(exc)}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
