"""`python -m mcc` runs the command line."""

from mcc.cli.main import main

if __name__ == "__main__":
    main()
