"""The viewer's modal screens (help, save) and a command palette that survives early keys."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.binding import Binding
from textual.command import CommandPalette
from textual.containers import Vertical, VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Input, Static

from .keys import help_text


class HelpScreen(ModalScreen):
    """Every key, from the key table the footer and the bindings use."""

    BINDINGS = [Binding("escape,question_mark,q", "dismiss", "close")]
    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll { width: 64; max-height: 90%; border: round $accent;
                                  background: $surface; padding: 0 1; height: auto; }
    """

    def compose(self) -> ComposeResult:
        with VerticalScroll():
            yield Static(help_text())


class SaveScreen(ModalScreen[str | None]):
    """Asks for a preset name; Enter saves, Esc cancels."""

    BINDINGS = [Binding("escape", "cancel", "cancel")]
    DEFAULT_CSS = """
    SaveScreen { align: center middle; }
    SaveScreen > Vertical { width: 50; height: auto; border: round $accent; background: $surface;
                            padding: 0 1; }
    """

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Static("Save preset as (Enter saves, Esc cancels):")
            yield Input(placeholder="name", id="name")

    def _close(self, result: str | None) -> None:
        # keys that arrive together (Enter Enter) can ask twice before the screen is gone:
        # only the screen on top may dismiss itself
        if self.is_current:
            self.dismiss(result)

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        self._close(event.value.strip() or None)

    def action_cancel(self) -> None:
        self._close(None)


class SafeCommandPalette(CommandPalette):
    """Textual 8.2's palette raises ``KeyError`` when PageUp/PageDown (or Home/End) reach its
    option list before the list has been laid out (ctrl+p then PageUp in one burst): its line
    index is still empty.  Such a key is dropped; once laid out, the list works as usual."""

    def _action_command_list(self, action: str) -> None:
        try:
            super()._action_command_list(action)
        except (KeyError, IndexError):
            pass
