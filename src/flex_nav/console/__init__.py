"""flex_nav.console: the web operator console's core (no rospy; the node is :mod:`flex_nav.nodes.console`).

- :mod:`~flex_nav.console.model` -- a runner's ``~structure`` JSON read into typed records, strictly.
- :mod:`~flex_nav.console.graph` -- the structure as SVG, laid out by Graphviz's ``dot``, ids from state paths.
- :mod:`~flex_nav.console.commands` -- every command from the browser validated before it reaches a runner.
- :mod:`~flex_nav.console.events` -- the runner's topics as small JSON events; answers matched to commands.
- :mod:`~flex_nav.console.server` -- the aiohttp app: the page, the websocket, the token and origin checks.
- :mod:`~flex_nav.console.errors` -- its typed errors.
- ``web/`` -- the page: plain HTML, CSS and JavaScript, served from the package.
"""
