from effects.cli.main import main

raise SystemExit(main())
