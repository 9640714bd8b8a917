"""Workflow: grid expansion, parallel execution with a resumable chunk store, the CF dataset."""
