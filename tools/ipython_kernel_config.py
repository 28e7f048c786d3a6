# The book's kernels (installed by make into .venv/etc/ipython): quiet about the one thing every
# kernel of ipykernel 7 prints, that it talks to its notebook over loopback TCP without
# encryption. Nothing else is changed or silenced.
import logging


class _NoUnencryptedTcpNotice(logging.Filter):
    def filter(self, record):
        return "running over TCP without encryption" not in record.getMessage()


logging.getLogger("IPKernelApp").addFilter(_NoUnencryptedTcpNotice())
