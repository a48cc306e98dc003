"""The rule machinery: the quantity graph and the rule table."""
