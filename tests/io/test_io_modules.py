"""The specification of the I/O module kinds (plclab.io.modules) is whole: every key names a
converter and a per-scan template that exist, every size is an address size, every fault and
choice is one the module class accepts."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from plclab.errors import PlcError
from plclab.io.modules import KINDS, ModuleKind, Param
from plclab.lang.addresses import SIZE_BYTES
from plclab.sim.transfers import TRANSFERS
from plclab.sim.wiring import CONVERTERS

SIGNAL = SimpleNamespace(name="X", type="real", unit="m", range=(0.0, 2.0))


def problems(kind: ModuleKind) -> list[str]:
    """What is wrong with a module kind's specification (empty: nothing)."""
    out = []
    if kind.direction not in ("in", "out", None):
        out.append(f"direction {kind.direction!r}")
    if kind.signal not in ("bool", "real", "any"):
        out.append(f"signal {kind.signal!r}")
    if kind.carries not in ("bit", "counts", "value"):
        out.append(f"carries {kind.carries!r}")
    elif not set(kind.sizes) <= set(SIZE_BYTES):
        out.append(f"sizes {kind.sizes}")
    for name, p in kind.params.items():
        if p.convert not in CONVERTERS:
            out.append(f"param {name}: converter {p.convert!r}")
        if (p.convert == "choice") != bool(p.choices):
            out.append(f"param {name}: choices")
    if kind.real_param and kind.real_param not in kind.params:
        out.append(f"real_param {kind.real_param!r}")
    templates = TRANSFERS.get(kind.transfer)
    if templates is None:
        out.append(f"transfer {kind.transfer!r}")
    else:
        for i, d in enumerate(("in", "out")):
            if kind.direction in (d, None) and templates[i] is None:
                out.append(f"transfer {kind.transfer!r} has no {d} template")
    if kind.build is None and (kind.faults or kind.transfer != "copy"):
        out.append("no build, but faults or a module transfer")
    return out


@pytest.mark.parametrize("name", list(KINDS))
def test_every_kind_is_whole(name):
    assert KINDS[name].name == name
    assert problems(KINDS[name]) == []


@pytest.mark.parametrize("kind, words", [
    (ModuleKind("x", "sideways", "", "bool", "bit", {}), "direction"),
    (ModuleKind("x", "in", "", "text", "bit", {}), "signal"),
    (ModuleKind("x", "in", "", "bool", "bytes", {}), "carries"),
    (ModuleKind("x", "in", "", "bool", "bit", {"a": Param("float", "")}), "converter"),
    (ModuleKind("x", "in", "", "bool", "bit", {"a": Param("choice", "")}), "choices"),
    (ModuleKind("x", "in", "", "bool", "bit", {}, real_param="threshold"), "real_param"),
    (ModuleKind("x", "in", "", "bool", "bit", {}, transfer="teleport"), "transfer"),
    (ModuleKind("x", "in", "", "real", "counts", {}, transfer="on_change"), "no in template"),
    (ModuleKind("x", None, "", "real", "counts", {}, transfer="sampled"), "no out template"),
    (ModuleKind("x", "in", "", "bool", "bit", {}, {"open": ""}), "no build"),
])
def test_the_check_catches_broken_kinds(kind, words):
    assert any(words in p for p in problems(kind)), problems(kind)


def built(spec: ModuleKind, **params):
    return spec.build(dict(params), SIGNAL)


@pytest.mark.parametrize("name", [n for n, k in KINDS.items() if k.build is not None])
def test_the_faults_are_the_ones_the_module_implements(name):
    kind = KINDS[name]
    assert kind.faults, f"module {name} has no faults to inject"
    for fault in kind.faults:
        m = built(kind)
        m.inject(fault)
        assert m.fault == fault
        m.clear()
        assert m.fault is None
    with pytest.raises(PlcError) as e:
        built(kind).inject("melted")
    assert e.value.code == "PLC9106" and all(f in e.value.message for f in kind.faults)


@pytest.mark.parametrize("name, param", [(n, p) for n, k in KINDS.items() if k.build
                                         for p, spec in k.params.items() if spec.choices])
def test_every_choice_builds(name, param):
    kind = KINDS[name]
    for choice in kind.params[param].choices:
        m = built(kind, **{param: choice})
        assert m is not None


def test_defaults_reach_the_module():
    ai = built(KINDS["ai"])
    assert ai.range.name == KINDS["ai"].params["signal_range"].default
    assert ai.format.convention == KINDS["ai"].params["convention"].default
    assert (ai.lo, ai.hi) == SIGNAL.range  # the plant signal's range
    ao = built(KINDS["ao"])
    assert ao.range.name == KINDS["ao"].params["signal_range"].default
    do = built(KINDS["do"])
    assert do.kind == KINDS["do"].params["kind"].default


def test_a_signal_in_ma_passes_through_the_transmitter():
    ma = SimpleNamespace(name="LEVEL_MA", type="real", unit="mA", range=(3.6, 21.0))
    ai = KINDS["ai"].build({}, ma)
    assert (ai.lo, ai.hi) == (4.0, 20.0)
    assert ai.sample(0.0, 12.0) == 27648 // 2


def test_settle_and_memoryless_follow_the_parameters():
    di = built(KINDS["di"], filter_ms=3.0, bounce_ms=2.0)
    assert KINDS["di"].settle(di) == pytest.approx(0.005)
    relay = built(KINDS["do"], kind="relay", close_ms=10.0, open_ms=5.0)
    assert KINDS["do"].settle(relay) == pytest.approx(0.010)
    assert KINDS["ai"].memoryless(built(KINDS["ai"]))
    assert not KINDS["ai"].memoryless(built(KINDS["ai"], noise=0.01))
    assert not KINDS["ai"].memoryless(built(KINDS["ai"], tau=0.5))
