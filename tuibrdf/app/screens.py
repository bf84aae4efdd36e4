"""The viewer's modal screens: help, save, typed value."""

from __future__ import annotations

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical, VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Input, OptionList, Static

from tuibrdf.app.guard import survives
from tuibrdf.app.keys import help_text


class HelpScreen(ModalScreen):
    """Every key, from the key table the footer and the bindings use."""

    BINDINGS = [Binding("escape,question_mark,q", "dismiss", "close")]
    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll { width: 64; max-width: 100%; max-height: 90%;
                                  border: round $accent;
                                  background: $surface; padding: 0 1; height: auto; }
    """

    def compose(self) -> ComposeResult:
        with VerticalScroll():
            yield Static(help_text())


class ReportScreen(ModalScreen):
    """A report to read (the check verdicts, key F): any of its keys closes it."""

    BINDINGS = [Binding("escape,F,q", "dismiss", "close")]
    DEFAULT_CSS = """
    ReportScreen { align: center middle; }
    ReportScreen > VerticalScroll { width: 96%; max-height: 96%; border: round $accent;
                                    background: $surface; padding: 0 1; height: auto; }
    """

    def __init__(self, body) -> None:
        super().__init__()
        self.body = body

    def compose(self) -> ComposeResult:
        with VerticalScroll():
            yield Static(self.body)


class SaveScreen(ModalScreen[str | None]):
    """Asks for a preset name; Enter saves, Esc cancels.  ``SaveScreen(refused)``:
    ``refused(name)`` says why a name cannot be saved (or None); the message shows here and
    the dialog stays open (what is typed next goes on into it, never to the viewer)."""

    def __init__(self, refused=lambda name: None) -> None:
        super().__init__()
        self.refused = refused

    BINDINGS = [Binding("escape", "cancel", "cancel")]
    DEFAULT_CSS = """
    SaveScreen { align: center middle; }
    SaveScreen > Vertical { width: 50; height: auto; border: round $accent; background: $surface;
                            padding: 0 1; }
    SaveScreen #error { color: $warning; }
    """

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Static("Save preset as (Enter saves, Esc cancels):")
            yield Input(placeholder="name", id="name")
            yield Static("", id="error")

    def _close(self, result: str | None) -> None:
        # keys that arrive together (Enter Enter) can ask twice before the screen is gone:
        # only the screen on top may dismiss itself
        if self.is_current:
            self.dismiss(result)

    @survives
    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        name = event.value.strip()
        why = self.refused(name) if name else None
        if why:
            self.query_one("#error", Static).update(Text(why))
            return
        self._close(name or None)

    @survives
    def action_cancel(self) -> None:
        self._close(None)


class ValueScreen(ModalScreen[str | None]):
    """Type a value: ``ValueScreen(prompt, current, apply, choices=())``.  ``apply(text)``
    validates and applies it, returning a message when refused: the message shows here and the
    input stays open; accepted, the screen closes with the text.  With ``choices`` (a long list
    such as the 100 MERL materials) typing filters a list of about 10 rows; ↑/↓ move in it,
    Enter applies the highlighted name, Esc cancels."""

    BINDINGS = [Binding("escape", "cancel", "cancel"),
                Binding("up", "move(-1)", show=False, priority=True),
                Binding("down", "move(1)", show=False, priority=True)]
    DEFAULT_CSS = """
    ValueScreen { align: center middle; }
    ValueScreen > Vertical { width: 60; max-width: 95%; height: auto; border: round $accent;
                             background: $surface; padding: 0 1; }
    ValueScreen OptionList { height: auto; max-height: 10; border: none; }
    ValueScreen #error { color: $warning; }
    """

    def __init__(self, prompt: str, current: str, apply, choices: tuple[str, ...] = ()) -> None:
        super().__init__()
        self.prompt, self.current, self.apply, self.choices = prompt, current, apply, choices
        self.shown: list[str] = list(choices)

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Static(Text(self.prompt), id="prompt")  # a file's names: never markup
            yield Input(value="" if self.choices else self.current, id="value",
                        placeholder="type to filter" if self.choices else self.current)
            if self.choices:
                yield OptionList(*map(Text, self.choices), id="choices")
            yield Static("", id="error")

    @survives
    def on_mount(self) -> None:
        if self.choices:
            options = self.query_one(OptionList)
            if self.current in self.choices:
                options.highlighted = self.choices.index(self.current)

    @survives
    def on_input_changed(self, event: Input.Changed) -> None:
        if not self.choices:
            return
        typed = event.value.strip().lower()
        self.shown = [c for c in self.choices if typed in c.lower()]
        options = self.query_one(OptionList)
        options.clear_options()
        options.add_options([Text(c) for c in self.shown])
        if self.shown:
            options.highlighted = 0
        self.query_one("#error", Static).update(
            Text("" if self.shown else f"no name contains {typed!r}"))

    @survives
    def action_move(self, delta: int) -> None:
        if self.choices and self.shown:
            options = self.query_one(OptionList)
            h = options.highlighted if options.highlighted is not None else -1
            options.highlighted = max(0, min(len(self.shown) - 1, h + delta))

    @survives
    def _submit(self, text: str) -> None:
        if not self.is_current:  # Enter Enter in one burst: the screen is already closing
            return
        error = self.apply(text)
        if error:
            self.query_one("#error", Static).update(Text(error))  # it quotes what was typed
        else:
            self.dismiss(text)

    @survives
    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        text = event.value.strip()
        if self.choices:
            options = self.query_one(OptionList)
            if options.highlighted is not None and self.shown:
                text = self.shown[options.highlighted]
        self._submit(text)

    @survives
    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self._submit(str(event.option.prompt))

    @survives
    def action_cancel(self) -> None:
        if self.is_current:
            self.dismiss(None)
