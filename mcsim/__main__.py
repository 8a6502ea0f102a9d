from mcsim.cli.main import console

console()
