"""Execute a notebook in place of a person (CI): every cell must run without an error.

Usage: python run_notebook.py NOTEBOOK.ipynb
"""

import sys
import tempfile

import nbformat
from nbclient import NotebookClient


def main(path: str) -> None:
    nb = nbformat.read(path, as_version=4)
    with tempfile.TemporaryDirectory() as work:
        NotebookClient(nb, timeout=900, kernel_name="python3", resources={"metadata": {"path": work}}).execute()
    print(f"{path}: {len(nb.cells)} cells executed")


if __name__ == "__main__":
    main(sys.argv[1])
