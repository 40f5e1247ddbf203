"""The chamber inside a host simulator (issue 50): chambers stepped in time on their map, many
at once (:mod:`.chambers`)."""
