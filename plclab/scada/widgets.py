"""The operator panel in a notebook: ipywidgets around a :class:`~plclab.scada.panel.Panel`.

No thread and no server: the notebook's buttons step the simulation (``Run 1 s``, ``Run 10 s``)
and act through the same :class:`Panel` methods as the browser page, so users and rights
behave the same way. ``ipywidgets`` is imported here only (``pip install ipywidgets``).

In a notebook::

    from plclab.scada.widgets import notebook_panel
    notebook_panel(Panel(sim, alarms, recipe))          # displays itself
"""

from __future__ import annotations

import html
from typing import Any

from plclab.errors import PlcError

from .panel import USERS, Panel


class NotebookPanel:
    """Widgets showing a panel's state, with buttons for its actions."""

    def __init__(self, panel: Panel) -> None:
        try:
            import ipywidgets as w
        except ImportError:
            raise PlcError("PLC6050", "the notebook panel needs ipywidgets: pip install "
                           "ipywidgets (or use plclab panel in a browser)") from None
        self.panel = panel
        self.w = w
        self.user = w.Dropdown(options=list(USERS), value=panel.user, description="user")
        self.user.observe(self._on_user, names="value")
        self.run1 = w.Button(description="Run 1 s")
        self.run10 = w.Button(description="Run 10 s")
        self.run1.on_click(lambda _: self.run(1.0))
        self.run10.on_click(lambda _: self.run(10.0))
        self.ack = w.Button(description="Acknowledge all", button_style="warning")
        self.ack.on_click(lambda _: self._act(panel.acknowledge))
        sigs = panel.sim.plant.signals
        self.buttons = {}
        for name, s in sigs.items():
            if s.kind == "panel" and s.type == "bool":
                b = w.Button(description=f"press {name}")
                b.on_click(lambda _, n=name: self._act(panel.press, n))
                self.buttons[name] = b
        self.records = {}
        for rec in (panel.recipe.records if panel.recipe is not None else {}):
            b = w.Button(description=f"load {rec}")
            b.on_click(lambda _, r=rec: self._act(panel.load_recipe, r))
            self.records[rec] = b
        self.signals = w.HTML()
        self.alarms = w.HTML()
        self.message = w.HTML()
        self.widget = w.VBox([
            w.HBox([self.user, self.run1, self.run10, self.ack]),
            w.HBox(list(self.buttons.values()) + list(self.records.values())),
            w.HBox([self.signals, self.alarms]), self.message])
        self.refresh()

    def _on_user(self, change: dict[str, Any]) -> None:
        self._act(self.panel.login, change["new"])

    def _act(self, fn: Any, *args: Any) -> None:
        try:
            fn(*args)
            self.message.value = ""
        except PlcError as e:
            self.message.value = f"<b style='color:#b00020'>{html.escape(e.message)}</b>"
        self.refresh()

    def run(self, seconds: float) -> None:
        """Advance the simulation by ``seconds`` of virtual time and redraw."""
        self.panel.advance(max(1, round(seconds / self.panel.sim.scan)))
        self.refresh()

    def refresh(self) -> None:
        st = self.panel.state()
        rows = "".join(
            f"<tr><td>{html.escape(s['name'])}</td><td>"
            f"{('ON' if s['value'] else 'off') if s['type'] == 'bool' else s['value']}"
            f" {html.escape(s['unit'])}</td></tr>" for s in st["signals"])
        self.signals.value = f"<b>t = {st['t']:.1f} s</b><table>{rows}</table>"
        alarms = "".join(
            f"<tr style='background:{html.escape(a['color'])}'><td>{html.escape(a['id'])}</td>"
            f"<td>{a['state']}</td><td>{html.escape(a['text'])}</td></tr>"
            for a in st["alarms"]) or "<tr><td>no alarms</td></tr>"
        log = "".join(f"<tr><td>{e['t']:.2f} s</td><td>{html.escape(e['id'])}</td>"
                      f"<td>{e['state']}</td><td>{html.escape(e['user'])}</td></tr>"
                      for e in reversed(st["log"][-8:]))
        self.alarms.value = (f"<b>alarms</b><table>{alarms}</table><b>log</b>"
                             f"<table>{log}</table>")
        rights = set(st["rights"])
        self.ack.disabled = "ack" not in rights
        for b in self.buttons.values():
            b.disabled = "operate" not in rights

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


def notebook_panel(panel: Panel) -> NotebookPanel:
    """The notebook panel of ``panel`` (displays itself as the last line of a cell)."""
    return NotebookPanel(panel)
