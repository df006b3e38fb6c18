"""`beltsim console` on a pseudo-terminal, for tests/console/console_test.py: the terminal's text as
the screen shows it, waits with deadlines on prompts and patterns (a failure shows the transcript),
keys sent as a user types them."""

import fcntl
import os
import pty
import re
import select
import signal
import struct
import termios
import time

# terminal control sequences readline writes (CSI, OSC, keypad/charset selection)
ANSI = re.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)|\x1b[()][0-9A-Za-z]|\x1b[=>78]")
PROMPT = re.compile(r"(?:^|\n)> $")
CONTINUATION = re.compile(r"(?:^|\n)>> $")

STARTUP_TIMEOUT = 20.0
TIMEOUT = 10.0


def clean(raw):
    """What the screen shows, roughly: escape sequences dropped, CR LF and lone CR as line ends."""
    text = ANSI.sub("", raw)
    text = text.replace("\r\n", "\n").replace("\r", "\n")
    return text.replace("\x07", "")


def child_env(tmp):
    env = dict(os.environ)
    env.update(TERM="xterm", BELTSIM_HISTORY=os.path.join(tmp, "history"), BELTSIM_TERM_IMAGES="off",
               INPUTRC="/dev/null", GALLIUM_DRIVER=env.get("GALLIUM_DRIVER", "llvmpipe"))
    env.pop("COLUMNS", None)
    env.pop("LINES", None)
    return env


class Console:
    """beltsim console on a pseudo-terminal (the pty is its controlling terminal, so ^C is SIGINT)."""

    def __init__(self, beltsim, test, tmp, args=(), script="scenario.lua"):
        self.test = test
        self.raw = ""
        self.status = None
        self.echoed_at_end = None
        argv = [beltsim, "console", script] + (["--"] + list(args) if args else [])
        env = child_env(tmp)
        pid, fd = pty.fork()
        if pid == 0:  # the child: the pty's slave is its stdin, stdout, stderr and controlling terminal
            try:
                os.chdir(tmp)
                fcntl.ioctl(0, termios.TIOCSWINSZ, struct.pack("HHHH", 50, 250, 0, 0))
                os.execve(beltsim, argv, env)
            except BaseException as e:  # noqa: BLE001 (the child must never return into unittest)
                os.write(2, ("cannot start %s: %s\n" % (beltsim, e)).encode())
            finally:
                os._exit(127)
        self.pid, self.fd = pid, fd
        self.wait_for(PROMPT, STARTUP_TIMEOUT, "the first prompt")

    # ---- reading

    def pump(self, timeout):
        """Reads what comes within timeout seconds; False once the terminal is closed."""
        r, _, _ = select.select([self.fd], [], [], max(timeout, 0))
        if not r:
            return True
        try:
            data = os.read(self.fd, 65536)
        except OSError:  # EIO: the child has gone and closed the slave
            data = b""
        if not data:
            return False
        self.raw += data.decode("utf-8", "replace")
        return True

    @property
    def screen(self):
        return clean(self.raw)

    def transcript(self):
        s = self.screen
        return ("\n---- transcript (cleaned, last 4000 characters) ----\n" + s[-4000:] +
                "\n---- raw tail ----\n" + repr(self.raw[-1500:]))

    def wait_for(self, pattern, timeout=TIMEOUT, what=None, start=0, raw=False):
        """Waits until pattern (a regex or a string) is on the screen after position start (in
        the bytes as written, escapes and bells included, with raw=True)."""
        deadline = time.monotonic() + timeout
        rx = re.compile(re.escape(pattern)) if isinstance(pattern, str) else pattern
        text = (lambda: self.raw) if raw else (lambda: self.screen)
        while True:
            m = rx.search(text(), start)
            if m:
                return m
            left = deadline - time.monotonic()
            if left <= 0:
                self.test.fail("no %s within %.0f s%s" % (what or repr(pattern), timeout, self.transcript()))
            if not self.pump(left):
                m = rx.search(text(), start)
                if m:
                    return m
                self.test.fail("the console ended before %s%s" % (what or repr(pattern), self.transcript()))

    def wait_prompt(self, start, timeout=TIMEOUT, continuation=False):
        """Waits for a prompt written after position start (the last thing on the screen)."""
        self.wait_for(CONTINUATION if continuation else PROMPT, timeout,
                      "continuation prompt '>> '" if continuation else "prompt '> '", start)

    # ---- writing

    def send(self, data):
        os.write(self.fd, data.encode())

    def complete(self, typed, expected, what, tabs="\t"):
        """Types typed (no Enter), then tabs; waits until expected (a regex or a string) is on the
        screen; returns the screen position before the typing."""
        mark = len(self.screen)
        self.send(typed)
        self.wait_for(typed, start=mark)
        self.send(tabs)
        self.wait_for(expected, what=what, start=mark)
        return mark

    def complete_nothing(self, typed):
        """Types typed, then Tab, and waits for readline's bell: a completion that found nothing.
        Returns the screen position before the typing."""
        mark = len(self.screen)
        self.send(typed)
        self.wait_for(typed, start=mark)
        raw_mark = len(self.raw)
        self.send("\t")
        self.wait_for("\x07", start=raw_mark, raw=True, what="the bell of a completion that found nothing")
        return mark

    def command(self, line, continuation=False, timeout=TIMEOUT):
        """Types line and Enter, waits for the next prompt; returns what the screen shows in between
        (the echo of the line included)."""
        mark = len(self.screen)
        self.send(line + "\r")
        self.wait_prompt(mark, timeout, continuation)
        return self.screen[mark:]

    # ---- ending

    def eof(self, timeout=TIMEOUT):
        """Ctrl-D; returns the exit status once the console has gone."""
        self.send("\x04")
        deadline = time.monotonic() + timeout
        while self.pump(deadline - time.monotonic()):
            if time.monotonic() > deadline:
                self.test.fail("the console did not end after Ctrl-D" + self.transcript())
        self.status = self._reap(deadline)
        return self.status

    def _reap(self, deadline):
        while True:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                # whether the terminal echoes as the console left it (the master still holds it)
                self.echoed_at_end = bool(termios.tcgetattr(self.fd)[3] & termios.ECHO)
                os.close(self.fd)
                self.pid = None
                return os.waitstatus_to_exitcode(status)
            if time.monotonic() > deadline:
                self.test.fail("the console did not exit" + self.transcript())
            time.sleep(0.02)

    def kill(self):
        if self.pid:
            try:
                os.kill(self.pid, signal.SIGKILL)
                os.waitpid(self.pid, 0)
            except OSError:
                pass
            try:
                os.close(self.fd)
            except OSError:
                pass
            self.pid = None
