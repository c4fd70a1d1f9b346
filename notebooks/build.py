"""Build the lab notebooks: one ``notebooks/<lab-id>.ipynb`` per lab, all of the same shape,
and its Russian edition ``notebooks/<lab-id>.ru.ipynb`` for every lab with a ``README.ru.md``.

    python notebooks/build.py            # write every notebook
    python notebooks/build.py --check    # exit 1 if a notebook is missing or out of date

Each notebook is made from the lab itself, so it stays in step with it: the task, the plant and
the I/O table come from the lab's ``README.md`` (which ``plclab lab show --update-readme`` keeps
in step with ``lab.toml``), the program cell starts with the lab's starter file. The cells:

1. the task, where it comes from and the plant (Markdown from the README);
2. set-up: imports, the lab, three small helpers (``simulate``, ``show_timing``, ``grade``);
3. **the student's program**, a Python string ``PROGRAM`` (ST or text LD). The cell carries the
   tag ``student-program``: the tests put the reference solution there;
4. a short run of one scenario with the lab's wiring (``plclab.sim.run``) and its timing
   diagram;
5. the lab's visible checks (``plclab.grade.check``): the feedback and the score;
6. questions to think about;
7. the quiz of the course chapter that teaches the lab (``plclab.course.quiz.quiz_cell``: the
   answers are a dict in the cell, so the notebook runs headless too).

The Russian edition takes its Markdown from ``README.ru.md`` and the texts below; its code
cells are the English ones, but for the language the set-up cell gives the feedback in
(``plclab.i18n.set_language``). The notebooks are committed as generated, without outputs.
Nothing here runs a simulation.
"""

from __future__ import annotations

import argparse
import re
import sys
import tomllib
from pathlib import Path

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
LABS = ROOT / "labs"

PROGRAM_TAG = "student-program"
"""Tag of the cell that holds the student's program."""

# Per lab: the scenario of the exploration run, how long to run it (None: the whole scenario),
# the window of the timing diagram (None: everything), and questions to think about.
LABS_CONFIG: dict[str, dict] = {
    "motor-start-stop": {
        "scenario": "start-stop",
        "duration": None,
        "window": (0.0, 12.0),
        "questions": [
            "Why is the stop button wired normally closed? What happens to the motor when the "
            "wire to STOP breaks?",
            "The overload relay already breaks the coil circuit in hardware. Why must the "
            "program still drop K1 when OVERLOAD is TRUE?",
            "RUN follows K1 a little later in the diagram. Where does the delay come from?",
        ],
    },
    "tank-two-position": {
        "scenario": "normal",
        "duration": "3min",
        "window": None,
        "questions": [
            "Between LS1 and LS2 the pump keeps what it was doing. Which part of "
            "`M := ((NOT LS1) OR M) AND (NOT LS2)` makes it remember?",
            "Move LS2 closer to LS1 (in your head): what happens to the number of pump starts "
            "per hour?",
        ],
    },
    "relay-thermostat": {
        "scenario": "warm-up",
        "duration": "8min",
        "window": None,
        "questions": [
            "How many times per hour does the contactor switch with H = 2 °C? With H = 0.5 °C?",
            "Why does the temperature go a little beyond 48 °C and 52 °C before it turns?",
        ],
    },
    "bottle-reject": {
        "scenario": "run",
        "duration": "15s",
        "window": (0.0, 15.0),
        "questions": [
            "A standing bottle wobbles as it passes the eyes. What would a reject rung without "
            "the 30 ms TON do?",
            "Why must the counters count edges and not the scans in which a beam is broken?",
        ],
    },
    "ventilation-fans": {
        "scenario": "two-faults",
        "duration": None,
        "window": (10.0, 40.0),
        "questions": [
            "5 Hz is five flashes per second. What T_ON and T_OFF give it, and why would "
            "T#200ms / T#200ms be wrong?",
            "After two faults, should the main power come back by itself when one fan is "
            "repaired? Argue for and against.",
            "Why does the standby fan stop again after the repair instead of running on?",
        ],
    },
    "pump-station": {
        "scenario": "surge",
        "duration": None,
        "window": None,
        "questions": [
            "The book's program starts pump 1 at WY without looking at DAWL. When does that go "
            "wrong?",
            "What happens with a stage time of 10 s? Of 10 minutes?",
            "Why are the starts of the pumps spread out by a few seconds?",
        ],
    },
    "water-boiler": {
        "scenario": "tap-open",
        "duration": None,
        "window": (50.0, 230.0),
        "questions": [
            "The trigger bit of NO_WATER is FALSE again at about 130 s, yet the alarm stays on "
            "the panel until 200 s. In which state is it in between?",
            "Why is NO_WATER an error (with acknowledgement) and LEVEL_HIGH only a warning?",
            "The analog alarm TEMP_HIGH has a deadband and a delay. What would the alarm log "
            "show without them if the temperature hovered at 75 °C with some noise?",
        ],
    },
    "bottling-recipes": {
        "scenario": "juice",
        "duration": None,
        "window": (10.0, 22.0),
        "questions": [
            "Where in the diagram does the bottle settle, and what would happen without it?",
            "The nectar record fills 0.30 l. At how many % of FILL_LEVEL does the valve close?",
            "Which values belong in a recipe and which in the program? Think of the settle time.",
        ],
    },
    "heater-pid": {
        "scenario": "warm-up-and-step",
        "duration": None,
        "window": None,
        "questions": [
            "Set TN := 0.0 (a P controller). How far below the set point does the water stay "
            "in the sustained-draw scenario, and how does that depend on KP?",
            "Call the controller every 10 s instead of every second. What changes?",
            "Why does the power stay at 100 % for minutes at the start, and why does that not "
            "make the temperature overshoot (anti-windup)?",
        ],
    },
    "press-safety": {
        "scenario": "taped-hand",
        "duration": None,
        "window": (0.0, 14.0),
        "questions": [
            "In the taped-hand scenario the right hand comes 2.5 s after the left one. What "
            "does your program do, and where in the code is the 0.5 s?",
            "Why does the piston go back up (and not down) when the light curtain is clear "
            "again?",
            "What limits the dose accuracy: the scan time, the valve lag or the encoder?",
            "Where in your program does the temperature control run, and does it still run "
            "while the sequence waits for the light curtain?",
        ],
    },
    "washing-machine": {
        "scenario": "silk",
        "duration": None,
        "window": None,
        "questions": [
            "Two transitions leave Fill. What decides which one fires when LEVEL_SW closes, and "
            "what would a simultaneous divergence FROM Fill TO (Boiling, Warming) do instead?",
            "The abort transitions have PRIORITY := 0. What happens in the scan in which the "
            "door opens just as Warming.T reaches 5 minutes, with and without the priority?",
            "HEATER(N) in Boiling and HEATER(S) in Boiling: draw both on the timing diagram. "
            "Which step would need HEATER(R)?",
        ],
    },
    "drive-homing": {
        "scenario": "drive-trip",
        "duration": None,
        "window": None,
        "questions": [
            "Add a fourth drive (a second belt). Which lines change in the program with the "
            "interface, and which in the classic one in solution/?",
            "Home() restarts the command's timeout. What happens to a drive with a broken home "
            "switch if the sequence calls Home() in every scan?",
            "The piston trips during homing. Why must the belt and the pump stop too, although "
            "nothing is wrong with them?",
        ],
    },
    "pedestrian-crossing": {
        "scenario": "slow-walker",
        "duration": None,
        "window": None,
        "questions": [
            "A pedestrian taps the button for 0.3 s while the cars are in their first 20 s of "
            "green. Which step remembers the tap, and what would be lost without it?",
            "WAIT_LAMP stays on for one scan of pedestrian green. Why one scan, and which rule of "
            "SFC evolution says so?",
            "In slow-walker PedClear lasts longer than 3 s. Read its step time in the trace: how "
            "long did the cars wait, and what ended the wait?",
        ],
    },
    # labs16 (issue 16): one lab per chapter that had none
    "bottle-packing": {
        "scenario": "run",
        "duration": "25s",
        "window": (0.0, 25.0),
        "questions": [
            "The sixth bottle stops in front of X1 when the belt stops. Why is it not counted "
            "again when the belt starts and the counter has been reset?",
            "TO_GO comes from a CTD and IN_BOX from a CTU. Which of the two would you show on "
            "the operator panel, and which one would you compare with the box size?",
            "What happens to the count if the operator presses STOP while a bottle is in the "
            "beam? Try it with a scenario action.",
        ],
    },
    "level-4-20ma": {
        "scenario": "wire-break",
        "duration": None,
        "window": (60.0, 180.0),
        "questions": [
            "The broken loop reads 32767 counts. What level would a program that trusts the "
            "number compute, and what would its pump do?",
            "Why does a 0-20 mA signal make a wire break invisible, and a 4-20 mA one not?",
            "A 12-bit card gives 4096 steps over 4-20 mA. How many millimetres of level is one "
            "step on this 2 m tank?",
        ],
    },
    "scan-timing": {
        "scenario": "start-stop",
        "duration": None,
        "window": (0.4, 0.7),
        "questions": [
            "REACTION_MS reads about 50 ms. Which parts of it are the relay output, the "
            "contactor, the input filter and the scan?",
            "Move the start/stop circuit into the slow task. What is the longest reaction now, "
            "and why can a press of 60 ms be lost?",
            "The fast task measures exactly 10 ms on this virtual PLC. What would a real PLC "
            "show, and what does a cycle overrun do to it?",
        ],
    },
    "modbus-operator": {
        "scenario": "operate",
        "duration": None,
        "window": None,
        "questions": [
            "Why does the PLC write 0 back into the command register? What could the station "
            "not tell without it?",
            "A station writes -200 into holding register 1. Which number travels in the "
            "Modbus frame, and what does the program's INT see?",
            "Run the solution with `plclab serve --plant tank` and drive it with "
            "`plclab.modbus.connect()`. Which register tells you that the PLC is alive?",
        ],
    },
}


QUESTIONS_RU: dict[str, list[str]] = {
    "motor-start-stop": [
        "Почему кнопку «Стоп» подключают размыкающим контактом? Что будет с двигателем, если "
        "оборвётся провод к STOP?",
        "Реле перегрузки и так размыкает цепь катушки аппаратно. Почему программа всё равно "
        "должна отключать K1, когда OVERLOAD равен TRUE?",
        "На диаграмме RUN следует за K1 с небольшой задержкой. Откуда она берётся?",
    ],
    "tank-two-position": [
        "Между LS1 и LS2 насос продолжает делать то, что делал. Какая часть "
        "`M := ((NOT LS1) OR M) AND (NOT LS2)` заставляет его помнить?",
        "Мысленно придвиньте LS2 ближе к LS1: что станет с числом пусков насоса в час?",
    ],
    "relay-thermostat": [
        "Сколько раз в час переключается контактор при H = 2 °C? При H = 0,5 °C?",
        "Почему температура немного выходит за 48 °C и 52 °C, прежде чем повернуть?",
    ],
    "bottle-reject": [
        "Стоящая бутылка покачивается, проходя мимо датчиков. Что сделала бы ступень "
        "отбраковки без TON на 30 мс?",
        "Почему счётчики должны считать фронты, а не циклы, в которых луч перекрыт?",
    ],
    "ventilation-fans": [
        "5 Гц — это пять вспышек в секунду. Какие T_ON и T_OFF это дают, и почему "
        "T#200ms / T#200ms было бы неверно?",
        "После двух неисправностей должно ли главное питание возвращаться само, когда один "
        "вентилятор отремонтирован? Приведите доводы за и против.",
        "Почему резервный вентилятор после ремонта снова останавливается, а не продолжает "
        "работать?",
    ],
    "pump-station": [
        "Программа учебника включает насос 1 по WY, не глядя на DAWL. Когда это приводит к "
        "беде?",
        "Что будет при времени ступени 10 с? 10 минут?",
        "Почему пуски насосов разнесены на несколько секунд?",
    ],
    "water-boiler": [
        "Бит-триггер NO_WATER снова FALSE примерно на 130 с, но авария остаётся на панели до "
        "200 с. В каком она состоянии в промежутке?",
        "Почему NO_WATER — ошибка (с квитированием), а LEVEL_HIGH — лишь предупреждение?",
        "У аналоговой аварии TEMP_HIGH есть мёртвая зона и задержка. Что показал бы журнал "
        "аварий без них, если бы температура колебалась около 75 °C с небольшим шумом?",
    ],
    "bottling-recipes": [
        "Где на диаграмме бутылка успокаивается, и что было бы без этого?",
        "Запись нектара наливает 0,30 л. При скольких % FILL_LEVEL закрывается клапан?",
        "Какие значения место в рецепте, а какие — в программе? Подумайте о времени "
        "успокоения.",
    ],
    "heater-pid": [
        "Поставьте TN := 0.0 (П-регулятор). Насколько ниже уставки остаётся вода в сценарии "
        "sustained-draw, и как это зависит от KP?",
        "Вызывайте регулятор каждые 10 с вместо каждой секунды. Что меняется?",
        "Почему в начале мощность минутами держится на 100 %, и почему от этого температура не "
        "перерегулирует (защита от интегрального насыщения)?",
    ],
    "press-safety": [
        "В сценарии taped-hand правая рука приходит через 2,5 с после левой. Что делает ваша "
        "программа, и где в коде эти 0,5 с?",
        "Почему поршень идёт обратно вверх (а не вниз), когда световая завеса снова "
        "свободна?",
        "Что ограничивает точность дозы: время цикла, запаздывание клапана или энкодер?",
        "Где в вашей программе выполняется регулирование температуры, и выполняется ли оно, "
        "пока последовательность ждёт световую завесу?",
    ],
    "washing-machine": [
        "Из Fill выходят два перехода. Что решает, какой сработает, когда замкнётся LEVEL_SW, "
        "и что сделало бы вместо этого параллельное ветвление FROM Fill TO (Boiling, Warming)?",
        "У переходов прерывания PRIORITY := 0. Что происходит в цикле, в котором дверца "
        "открывается как раз когда Warming.T доходит до 5 минут, с приоритетом и без него?",
        "HEATER(N) в Boiling и HEATER(S) в Boiling: нарисуйте оба на временной диаграмме. "
        "Какому шагу понадобился бы HEATER(R)?",
    ],
    "drive-homing": [
        "Добавьте четвёртый привод (вторую ленту). Какие строки меняются в программе с "
        "интерфейсом, а какие — в классической из solution/?",
        "Home() перезапускает тайм-аут команды. Что будет с приводом со сломанным датчиком "
        "исходной позиции, если последовательность вызывает Home() в каждом цикле?",
        "У поршня срабатывает защита во время реферирования. Почему должны остановиться и "
        "лента, и насос, хотя с ними всё в порядке?",
    ],
    "pedestrian-crossing": [
        "Пешеход касается кнопки на 0,3 с, пока у машин идут первые 20 с зелёного. Какой шаг "
        "запоминает касание, и что потерялось бы без него?",
        "WAIT_LAMP горит ещё один цикл зелёного для пешеходов. Почему один цикл, и какое "
        "правило эволюции SFC это определяет?",
        "В slow-walker PedClear длится дольше 3 с. Прочитайте время этого шага в трассе: "
        "сколько ждали машины, и что закончило ожидание?",
    ],
    "bottle-packing": [
        "Шестая бутылка останавливается перед X1, когда встаёт конвейер. Почему её не "
        "считают снова, когда конвейер трогается, а счётчик сброшен?",
        "TO_GO берётся из CTD, а IN_BOX — из CTU. Какой из двух вы показали бы на панели "
        "оператора, а какой сравнивали бы с размером ящика?",
        "Что будет со счётом, если оператор нажмёт STOP, пока бутылка в луче? Попробуйте "
        "это действием сценария.",
    ],
    "level-4-20ma": [
        "Оборванная петля даёт 32767 ед. АЦП. Какой уровень вычислит программа, доверяющая "
        "числу, и что сделает её насос?",
        "Почему сигнал 0-20 мА делает обрыв провода невидимым, а 4-20 мА — нет?",
        "12-битный модуль даёт 4096 ступеней на 4-20 мА. Сколько миллиметров уровня — одна "
        "ступень на этом баке высотой 2 м?",
    ],
    "scan-timing": [
        "REACTION_MS показывает около 50 мс. Какие его части приходятся на релейный выход, "
        "контактор, входной фильтр и цикл?",
        "Перенесите схему пуска/останова в медленную задачу. Какова теперь самая долгая "
        "реакция, и почему нажатие в 60 мс может потеряться?",
        "Быстрая задача на этом виртуальном ПЛК измеряет ровно 10 мс. Что показал бы "
        "настоящий ПЛК, и что с этим делает превышение времени цикла?",
    ],
    "modbus-operator": [
        "Почему ПЛК записывает 0 обратно в регистр команды? Чего станция не смогла бы узнать "
        "без этого?",
        "Станция записывает -200 в регистр хранения 1. Какое число передаётся в кадре "
        "Modbus, и что видит INT программы?",
        "Запустите решение командой `plclab serve --plant tank` и управляйте им через "
        "`plclab.modbus.connect()`. Какой регистр говорит, что ПЛК жив?",
    ],
}
"""The questions of LABS_CONFIG in Russian (the same number, the same order)."""

DEFAULT_QUESTIONS_RU = [
    "Какой критерий было труднее всего выполнить, и что на временной диаграмме показало "
    "вам почему?",
    "Что пошло бы не так на настоящей машине, если бы программа ошибалась на один цикл?",
]


# ---------------------------------------------------------------------------- README


def readme_sections(text: str) -> tuple[str, str, dict[str, str]]:
    """(title, intro, {heading: body}) of a lab README."""
    lines = text.splitlines()
    title = lines[0].lstrip("# ").strip() if lines and lines[0].startswith("# ") else ""
    parts = re.split(r"^## +(.+?)\s*$", "\n".join(lines[1:]), flags=re.MULTILINE)
    intro = parts[0].strip()
    sections = {parts[i].strip(): parts[i + 1].strip() for i in range(1, len(parts) - 1, 2)}
    return title, intro, sections


def io_table(body: str) -> str:
    """The table between the README's generated markers (the markers dropped)."""
    out = [ln for ln in body.splitlines() if not ln.strip().startswith("<!--")]
    return "\n".join(out).strip()


def program_source(text: str) -> str:
    """The source of the program cell for a program text."""
    if '"""' in text:
        raise ValueError('a program text holds """; the notebook cell cannot quote it')
    return ("# Your program (ST or text LD). Edit it here, then run all cells below.\n"
            f'PROGRAM = r"""\n{text.strip()}\n"""\n')


def starter_text(lab_dir: Path) -> str:
    for ext in (".st", ".ld", ".il"):
        p = lab_dir / f"starter{ext}"
        if p.is_file():
            return p.read_text(encoding="utf-8")
    raise FileNotFoundError(f"{lab_dir}: no starter file")


# ---------------------------------------------------------------------------- cells

SETUP = '''\
# Set-up: plclab, the lab, and four helpers. Nothing to change here.
import io
import logging
import os
import re
import tempfile
import warnings
from pathlib import Path
from types import SimpleNamespace

import matplotlib
import numpy as np
from IPython.display import Image, Markdown, display

import plclab
from plclab.errors import PlcError
from plclab.grade import check, load_lab
from plclab.grade.commands import failure_picture, first_failure
from plclab.grade.criteria import criterion_limits
from plclab.grade.engine import guess_language
from plclab.grade.feedback import criterion_picture, render_feedback
from plclab.i18n import set_language
from plclab.i18n_labs import localize_result
from plclab.sim import run
from plclab.viz import timing_diagram
from plclab.viz.from_trace import plant_limits, series
from plclab.viz.layout import signal_labels
from plclab.viz.series import Series

warnings.simplefilter("ignore", DeprecationWarning)
warnings.simplefilter("ignore", PendingDeprecationWarning)
warnings.simplefilter("ignore", FutureWarning)
warnings.simplefilter("ignore", RuntimeWarning)  # NumPy on odd traces: the feedback says it
warnings.filterwarnings("ignore", category=UserWarning, module="matplotlib")
logging.getLogger("matplotlib").setLevel(logging.ERROR)  # no font-cache message on stderr
matplotlib.use("Agg")  # pictures are shown as PNG images below, no GUI window

if (Path.cwd().parent / "labs").is_dir():  # running from the repository's notebooks/ folder
    os.environ.setdefault("PLCLAB_LABS", str(Path.cwd().parent / "labs"))

LAB = {lab_id!r}
lab = load_lab(LAB)
set_language({lang!r})  # the language of the feedback below: "en" or "ru"


def simulate(program, scenario, duration=None):
    """Run the program on the lab's plant and wiring in one of its scenarios: a Trace, or
    None (with the compiler's or the simulator's message) when it cannot run."""
    spec = lab.scenario(scenario)
    try:
        plc = plclab.loads(program, f"program.{{guess_language(program)}}", cycle_time=lab.scan)
        return run(plc, plant=lab.plant, wiring=lab.wiring, scan=lab.scan, seed=spec.seed,
                   scenario=spec.scenario(duration), watch=lab.all_watch(spec),
                   plant_params={{**lab.plant_params, **spec.plant_params}})
    except PlcError as e:
        print(f"The program cannot run yet:\\n{{e}}")
        return None


def what_is_checked(trace, scenario, names):
    """What the scenario's criteria check, on the diagram's rows: set points and levels
    (dashed lines), bands (shaded), and each counted switching as a counter row with the
    most it may reach (as `plclab lab check --png` draws a failure)."""
    lines, bands, rows = {{}}, {{}}, []
    for crit in lab.criteria_for(scenario):
        drawing = criterion_picture(trace, crit, names)
        for row, found in drawing.thresholds.items():
            have = lines.setdefault(row, [])
            have += [x for x in found if all(abs(x[0] - y) > 1e-9 for y, _ in have)]
        for row, found in drawing.bands.items():
            have = bands.setdefault(row, [])
            have += [b for b in found if b not in have]
        for lim in criterion_limits(crit):
            if lim.kind != "count" or not lim.signal or lim.value is None \\
                    or lim.signal not in trace:
                continue
            col = trace.resolve(lim.signal)
            t, v = np.asarray(trace.time, float), np.asarray(trace[col], float)
            n = np.concatenate([[0], np.cumsum(np.abs(np.diff(v)) > 0.5)])
            per = re.search(r"in ([\\d.]+) s", lim.label)
            name = f"{{col}} switchings"
            if per:  # a count over a sliding window: the switchings of the last W s
                w = float(per.group(1))
                n = n - n[np.clip(np.searchsorted(t, t - w), 0, len(n) - 1)]
                name += f" in {{per.group(1)}} s"
            if all(r.name != name for r in rows):
                rows.append(Series(name, t, n.astype(float), "real"))  # a step plot
            words = "at most" if lim.label.startswith("at most") else "fewer than"
            lines.setdefault(name, []).append((float(lim.value), words))
    return lines, bands, rows


def show_timing(trace, signals=None, t0=None, t1=None, title="", scenario=None):
    """A timing diagram of the trace, shown as a PNG image, with what the scenario's
    criteria check drawn on it."""
    if trace is None:
        return
    names = [trace.resolve(s) for s in (signals or lab.diagram_signals) if s in trace]
    lines, bands, counts = what_is_checked(trace, scenario, names) if scenario else ({{}}, {{}}, [])
    for row, found in plant_limits(trace).items():  # switch heights, rims
        have = lines.setdefault(row, [])
        have += [x for x in found if all(abs(x[0] - y) > 1e-9 for y, _ in have)]
    labels = signal_labels(lab.io, trace)  # PUMP %QX0.0: the program's name and address
    rows = []
    for s in series(trace, names) + counts:  # a wire's plant and PLC side: one row
        shown = labels.get(s.name, s.name)
        if any(r.name == shown for r in rows):
            continue
        lines = {{(shown if k == s.name else k): v for k, v in lines.items()}}
        bands = {{(shown if k == s.name else k): v for k, v in bands.items()}}
        s.name = shown
        rows.append(s)
    fig = timing_diagram(rows, t0=t0, t1=t1, title=title, width=9.0, thresholds=lines,
                         bands=bands, fixed_layout=True)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=80)
    import matplotlib.pyplot as plt

    plt.close(fig)
    display(Image(data=buf.getvalue()))


def show_first_failure(result):
    """The first failing scenario around the moment of its first failure, the failed
    criterion's limits drawn: the picture `plclab lab check FILE --png F` draws."""
    first = first_failure(lab, result.tests, result.traces) if result.traces else None
    if first is None:
        print("every visible scenario passed: no failure to show")
        return None
    with tempfile.TemporaryDirectory() as tmp:
        png = Path(tmp) / "first-failure.png"
        said = failure_picture(lab, result.traces[first.scenario], first,
                               SimpleNamespace(png=str(png), window=None, signals=None))
        display(Image(data=png.read_bytes()))
    print("first failure:", said.rsplit(" (", 1)[-1].rstrip(")"))
    return first


def grade(program):
    """The lab's visible scenarios and criteria on the program: feedback and score."""
    result = check(LAB, program)
    shown, _ = localize_result(result, lab)  # the feedback in the notebook's language
    display(Markdown(render_feedback(shown)))
    print(f"score: {{result.score:g}}/{{result.max_score:g}}")
    if result.score < result.max_score:
        show_first_failure(result)
    return result


print(lab)
'''

EXPLORE = '''\
# A run of the scenario `{scenario}`{dur_text} on the simulated plant, with the lab's wiring.
trace = simulate(PROGRAM, {scenario!r}, duration={duration!r})
show_timing(trace, t0={t0!r}, t1={t1!r}, title={title!r}, scenario={scenario!r})
if trace is not None:
    print("events (kind: count, first time):", trace.event_counts())
'''

GRADE = '''\
# The visible scenarios and criteria of the lab: what passed, what failed, hints; after a
# failure, the first failing scenario at the moment it failed, with the criterion's limits.
result = grade(PROGRAM)
'''

RERUN = '''\\
# In rerun's viewer: after a failed check the graded run (one viewer per scenario, the first
# failure first, its cursor at the failure, the criteria's limits drawn), else the run above.
# rerun-notebook 0.41 serves its viewer from your machine: works offline.
from plclab.viz import notebook as rerun_view

if rerun_view.available() and result is not None and result.score < result.max_score:
    rerun_view.show(result, lab=lab, limits={{c.name: criterion_limits(c) for c in lab.criteria}})
elif trace is not None and rerun_view.available():
    rerun_view.show(trace, lab=lab, scenario={scenario!r},
                    limits={{c.name: criterion_limits(c) for c in lab.criteria}})
elif trace is not None:
    print("To see the run in rerun here: pip install 'rerun-notebook==0.41.*'")
'''


QUIZ_CHAPTER = {"motor-start-stop": 3, "tank-two-position": 2, "relay-thermostat": 12,
                "bottle-reject": 6, "heater-pid": 12, "ventilation-fans": 10,
                "pump-station": 10, "press-safety": 17}
"""The chapter whose quiz ends a lab's notebook (default: the last chapter its lab.toml names)."""

QUIZ = """\
from plclab.course.quiz import quiz_cell

answers = {{}}   # your answers by question number, e.g. {{1: "2", 3: "16"}}; then run the cell
quiz_cell({chapter}, answers)
"""


def quiz_chapter(lab_id: str) -> int | None:
    if lab_id in QUIZ_CHAPTER:
        return QUIZ_CHAPTER[lab_id]
    data = tomllib.loads((LABS / lab_id / "lab.toml").read_text(encoding="utf-8"))
    return (data.get("chapters") or [None])[-1]


LANGUAGES = ("en", "ru")
"""The editions: English (``<lab>.ipynb``) and Russian (``<lab>.ru.ipynb``)."""

SECTIONS = {
    "en": {"task": "Your task", "requirements": "Requirements",
           "source": "Where this comes from", "plant": "The plant", "io": "I/O table",
           "grading": "Grading"},
    "ru": {"task": "Ваша задача", "requirements": "Требования", "source": "Откуда это",
           "plant": "Объект управления", "io": "Таблица входов и выходов", "grading": "Оценка"},
}
"""The README headings a notebook takes its sections from, in each language."""

TEXTS = {
    "en": {
        "intro": ("*Lab `{lab}` — a plclab notebook.* Write your program in the cell marked "
                  "**Your program**, run the notebook from the top (Run All), read the timing "
                  "diagram and the feedback, improve, repeat. The same checks run with "
                  "`plclab lab check {lab} FILE`; the graded run adds hidden scenarios."),
        "io": "Declare these addresses in your program (`AT %IX0.0` ...):",
        "setup": "Set-up",
        "program": ("## Your program\n\nThe program is a Python string: Structured Text, or a "
                    "ladder diagram in plclab's text LD. It starts as the lab's starter file."),
        "run": ("## Run it on the plant\n\nOne scenario of the lab, simulated with the lab's "
                "wiring (`plclab.sim.run`). The timing diagram shows the signals over time; "
                "`trace` holds every signal (`trace['NAME']`, `trace.value_at('NAME', t)`)."),
        "check": ("## Check it\n\nThe lab's visible scenarios and criteria "
                  "(`plclab.grade.check`), with the feedback a grader gives. The last line is "
                  "your score."),
        "rerun": ("## The run in rerun\n\nAn interactive timeline (the view of "
                  "`plclab lab check {lab} FILE --rrd run.rrd`): after a failed check it opens "
                  "on the first failing scenario at its first failure, else it shows the run "
                  "above. Scrub the time, zoom into a moment, watch the plant."),
        "graded": "What is graded",
        "questions": "Questions",
        "quiz": ("## Quiz\n\nThe quiz of chapter {chapter} of the course (`plclab quiz "
                 "{chapter}` in a terminal). Each answer gets its feedback."),
    },
    "ru": {
        "intro": ("*Работа `{lab}` — блокнот plclab.* Напишите программу в ячейке **Ваша "
                  "программа**, выполните блокнот сверху донизу (Run All), прочитайте временную "
                  "диаграмму и отзыв, исправьте, повторите. Те же проверки выполняет "
                  "`plclab --lang ru lab check {lab} ФАЙЛ`; при оценке добавляются скрытые "
                  "сценарии."),
        "io": "Объявите эти адреса в своей программе (`AT %IX0.0` ...):",
        "setup": "Подготовка",
        "program": ("## Ваша программа\n\nПрограмма — строка Python: структурированный текст "
                    "или релейно-контактная схема в текстовом LD plclab. Вначале это файл "
                    "заготовки работы."),
        "run": ("## Запустите её на объекте\n\nОдин сценарий работы, смоделированный с "
                "подключением работы (`plclab.sim.run`). Временная диаграмма показывает "
                "сигналы во времени; `trace` хранит каждый сигнал (`trace['NAME']`, "
                "`trace.value_at('NAME', t)`)."),
        "check": ("## Проверьте её\n\nВидимые сценарии и критерии работы "
                  "(`plclab.grade.check`) с отзывом, какой даёт проверка. Последняя строка — "
                  "ваша оценка."),
        "rerun": ("## Прогон в rerun\n\nИнтерактивная шкала времени (вид "
                  "`plclab lab check {lab} ФАЙЛ --rrd run.rrd`): после непройденной проверки "
                  "она открывается на первом непройденном сценарии в момент первой неудачи, "
                  "иначе показывает прогон выше. Двигайте время, приближайте момент, следите "
                  "за объектом."),
        "graded": "Что оценивается",
        "questions": "Вопросы",
        "quiz": ("## Тест\n\nТест главы {chapter} курса (`plclab quiz {chapter}` в "
                 "терминале). На каждый ответ есть отзыв."),
    },
}
"""The notebook's own Markdown in each language."""


def notebook_path(lab_id: str, lang: str = "en") -> Path:
    """``notebooks/<lab>.ipynb``, or ``notebooks/<lab>.<lang>.ipynb`` for another edition."""
    return HERE / (f"{lab_id}.ipynb" if lang == "en" else f"{lab_id}.{lang}.ipynb")


def editions(lab_id: str) -> list[str]:
    """The languages the lab's notebook is built in: English, and each language the lab has
    a ``README.<lang>.md`` for."""
    return [g for g in LANGUAGES if g == "en" or (LABS / lab_id / f"README.{g}.md").is_file()]


def questions(lab_id: str, lang: str = "en") -> list[str]:
    """The questions to think about of a lab's notebook in ``lang``."""
    english = lab_config(lab_id)["questions"]
    if lang == "en":
        return english
    got = QUESTIONS_RU.get(lab_id, DEFAULT_QUESTIONS_RU if english is DEFAULT_QUESTIONS else [])
    if len(got) != len(english):
        raise ValueError(f"{lab_id}: {len(english)} questions in English, {len(got)} in "
                         f"{lang}: translate them in QUESTIONS_RU")
    return got


def build_notebook(lab_id: str, lang: str = "en") -> nbformat.NotebookNode:
    """The notebook of one lab in ``lang``."""
    lab_dir = LABS / lab_id
    cfg = lab_config(lab_id)
    words, heads = TEXTS[lang], SECTIONS[lang]
    name = "README.md" if lang == "en" else f"README.{lang}.md"
    readme = (lab_dir / name).read_text(encoding="utf-8")
    # the README's links to the course are relative to labs/ID/; a notebook sits in notebooks/
    readme = readme.replace("](../../course/", "](../course/")
    title, intro, sec = readme_sections(readme)
    cells = []
    head = [f"# {title}", "", words["intro"].format(lab=lab_id), "", intro]
    cells.append(new_markdown_cell("\n".join(head).strip()))
    for key in ("task", "requirements", "source", "plant"):  # as the README states them
        if heads[key] in sec:
            cells.append(new_markdown_cell(f"## {heads[key]}\n\n" + sec[heads[key]]))
    if heads["io"] in sec:
        cells.append(new_markdown_cell(f"## {heads['io']}\n\n{words['io']}\n\n"
                                       + io_table(sec[heads["io"]])))
    cells.append(new_markdown_cell(f"## {words['setup']}"))
    cells.append(new_code_cell(SETUP.format(lab_id=lab_id, lang=lang)))
    cells.append(new_markdown_cell(words["program"]))
    prog = new_code_cell(program_source(starter_text(lab_dir)))
    prog.metadata["tags"] = [PROGRAM_TAG]
    cells.append(prog)
    dur = cfg["duration"]
    t0, t1 = cfg["window"] if cfg["window"] else (None, None)
    cells.append(new_markdown_cell(words["run"]))
    cells.append(new_code_cell(EXPLORE.format(
        scenario=cfg["scenario"], duration=dur, t0=t0, t1=t1,
        dur_text=f" (the first {dur})" if dur else "",
        title=f"{lab_id}: {cfg['scenario']}")))
    cells.append(new_markdown_cell(words["check"]))
    cells.append(new_code_cell(GRADE))
    cells.append(new_markdown_cell(words["rerun"].format(lab=lab_id)))
    cells.append(new_code_cell(RERUN.format(scenario=cfg["scenario"])))
    if heads["grading"] in sec:
        cells.append(new_markdown_cell(f"## {words['graded']}\n\n" + sec[heads["grading"]]))
    qs = "\n".join(f"{i}. {q}" for i, q in enumerate(questions(lab_id, lang), 1))
    cells.append(new_markdown_cell(f"## {words['questions']}\n\n" + qs))
    chapter = quiz_chapter(lab_id)
    if chapter is not None:
        cells.append(new_markdown_cell(words["quiz"].format(chapter=chapter)))
        cells.append(new_code_cell(QUIZ.format(chapter=chapter)))
    nb = new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python",
                                 "name": "python3"}
    nb.metadata["language_info"] = {"name": "python"}
    nb.metadata["plclab"] = {"lab": lab_id, "generated_by": "notebooks/build.py"}
    if lang != "en":
        nb.metadata["plclab"]["lang"] = lang
    tag = lab_id if lang == "en" else f"{lab_id}-{lang}"
    for i, c in enumerate(nb.cells):
        c["id"] = f"{tag}-{i:02d}"
    return nb


DEFAULT_QUESTIONS = [
    "Which criterion was the hardest to meet, and what in the timing diagram showed you why?",
    "What would go wrong on the real machine if the program were off by one scan?",
]


def lab_config(lab_id: str) -> dict:
    """The notebook settings of a lab: from LABS_CONFIG, else its first visible scenario."""
    if lab_id in LABS_CONFIG:
        return LABS_CONFIG[lab_id]
    data = tomllib.loads((LABS / lab_id / "lab.toml").read_text(encoding="utf-8"))
    scenarios = [s for s in data.get("scenario", []) if s.get("visible", True)]
    return {"scenario": scenarios[0]["name"], "duration": None, "window": None,
            "questions": DEFAULT_QUESTIONS}


def lab_ids() -> list[str]:
    """Every lab of the repository (a folder of labs/ with a lab.toml): the configured ones
    first, in the course's order, then the others by name."""
    found = sorted(p.name for p in LABS.iterdir() if (p / "lab.toml").is_file())
    return [k for k in LABS_CONFIG if k in found] + [k for k in found if k not in LABS_CONFIG]


def render(nb: nbformat.NotebookNode) -> str:
    return nbformat.writes(nb) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="only check that the notebooks are "
                    "up to date")
    ap.add_argument("labs", nargs="*", help="lab ids (default: all)")
    ns = ap.parse_args(argv)
    stale = []
    for lab_id in ns.labs or lab_ids():
        for lang in editions(lab_id):
            nb = build_notebook(lab_id, lang)
            nbformat.validate(nb)
            text = render(nb)
            path = notebook_path(lab_id, lang)
            if ns.check:
                if not path.is_file() or path.read_text(encoding="utf-8") != text:
                    stale.append(path.name)
                continue
            path.write_text(text, encoding="utf-8")
            print(f"wrote {path.relative_to(ROOT)}")
    if stale:
        print("out of date: " + ", ".join(stale) + " (run: python notebooks/build.py)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
