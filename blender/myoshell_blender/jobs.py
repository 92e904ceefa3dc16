"""One module call per operator, run where Blender stays responsive.

From a script (`bpy.ops.myoshell.…()`, or Blender without a window) the call runs at once in
`execute`. From the panel (`invoke` with a window) it runs on a worker thread while a timer updates
the progress indicator and the status bar: the module releases the GIL while it builds and settles,
so Blender's UI keeps drawing. Only the worker touches the module; only the main thread touches bpy.
Every failure ends as a Blender report, never a traceback.
"""

import threading
import time
import traceback
import warnings


def _module_errors():
    from . import head_mesh
    errors = (ValueError, RuntimeError, OSError, ImportError, head_mesh.HeadError)
    return errors


def message(e):
    text = str(e).strip() or type(e).__name__
    return text if isinstance(e, _module_errors()) else "internal error (%s: %s)" % (type(e).__name__, text)


class Work:
    """The worker's side: fn() run with its warnings recorded."""

    def __init__(self, fn):
        self.fn = fn
        self.result = None
        self.error = None
        self.warnings = []
        self.started = time.monotonic()
        self.thread = None

    def run(self):
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                self.result = self.fn()
            self.warnings = [str(w.message) for w in caught]
        except Exception as e:  # reported by the main thread
            if not isinstance(e, _module_errors()):
                traceback.print_exc()  # a bug of ours: the console keeps the trace for a report
            self.error = e

    def start(self):
        self.thread = threading.Thread(target=self.run, name="myoshell", daemon=True)
        self.thread.start()

    def elapsed(self):
        return time.monotonic() - self.started


class ModuleJobOperator:
    """Mixin: subclasses define title, expected_seconds, prepare(context) -> fn and
    finish(context, result) -> report text."""

    title = "Myoshell"
    expected_seconds = 10.0
    _timer = None
    _work = None

    # -- the two sides --------------------------------------------------------------------------
    def _begin(self, context):
        self._work = Work(self.prepare(context))
        wm = context.window_manager
        wm.progress_begin(0, 100)
        wm.progress_update(1)
        self._status(context, "%s…" % self.title)

    def _end(self, context):
        context.window_manager.progress_end()
        self._status(context, None)

    def _complete(self, context):
        work = self._work
        for w in work.warnings:
            self.report({'WARNING'}, w)
        if work.error is not None:
            self.report({'ERROR'}, message(work.error))
            return {'CANCELLED'}
        context.window_manager.progress_update(90)
        try:
            text = self.finish(context, work.result)
        except Exception as e:
            if not isinstance(e, _module_errors()):
                traceback.print_exc()
            self.report({'ERROR'}, message(e))
            return {'CANCELLED'}
        self.report({'INFO'}, text)
        return {'FINISHED'}

    @staticmethod
    def _status(context, text):
        ws = getattr(context, "workspace", None)
        if ws is not None:
            ws.status_text_set(text)

    # -- Blender's entry points -----------------------------------------------------------------
    def execute(self, context):
        try:
            self._begin(context)
        except Exception as e:
            self.report({'ERROR'}, message(e))
            return {'CANCELLED'}
        try:
            self._work.run()
            return self._complete(context)
        finally:
            self._end(context)

    def invoke(self, context, event):
        if context.window is None or getattr(context.window_manager, "is_interface_locked", False):
            return self.execute(context)
        try:
            self._begin(context)
        except Exception as e:
            self.report({'ERROR'}, message(e))
            return {'CANCELLED'}
        self._work.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.2, window=context.window)
        wm.modal_handler_add(self)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type != 'TIMER':
            return {'PASS_THROUGH'}
        work = self._work
        if work.thread.is_alive():
            t = work.elapsed()
            # The module reports no progress of its own: the bar follows the expected time and
            # stops short of the end until the work is done.
            context.window_manager.progress_update(min(85, 1 + 84 * t / self.expected_seconds))
            self._status(context, "%s… %.0f s" % (self.title, t))
            return {'RUNNING_MODAL'}
        context.window_manager.event_timer_remove(self._timer)
        try:
            return self._complete(context)
        finally:
            self._end(context)
