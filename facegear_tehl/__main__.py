from facegear_tehl.cli import main

main()
