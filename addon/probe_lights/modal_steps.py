"""What the add-on's step-by-step operators share (Measure tradeoff, Bake animation): one step a timer event, so
the interface stays live; the progress bar and a status-bar line say how far it is; Esc stops between steps."""


class ModalSteps:
    """Mixed into an operator that defines _status_text() (the status bar's line) and runs its own modal()."""

    def _start_steps(self, context, total):
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.01, window=context.window)
        wm.progress_begin(0, total)
        wm.modal_handler_add(self)
        self._show_progress(context, 0)
        return {"RUNNING_MODAL"}

    def _show_progress(self, context, done):
        context.window_manager.progress_update(done)
        if context.workspace is not None:
            context.workspace.status_text_set(self._status_text())

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        for area in context.screen.areas if context.screen else ():
            area.tag_redraw()
