"""Reports, figures and the console command."""
