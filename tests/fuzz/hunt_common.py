"""Shared by the session-29 hunt scripts (certificate_mutations.py, degenerate_models.py)."""
import subprocess

# texts that mean a crash, an abort or an uncaught exception, whatever the exit code
CRASH_TEXTS = ('terminate called', 'Assertion', 'Segmentation', 'Sanitizer', 'what():', 'CGAL ERROR')


def run(args, timeout=120):
    """(exit code or 'timeout', stdout, stderr) of one command"""
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=timeout, errors='replace')
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return 'timeout', '', ''


def crash_problems(rc, text):
    """what is wrong with a run, crash-wise: a time-out, a signal or abort, a crash text"""
    problems = []
    if rc == 'timeout':
        problems.append('timeout')
    elif rc < 0 or rc >= 128:
        problems.append('signal/abort rc=%s' % rc)
    problems += ['text: ' + bad for bad in CRASH_TEXTS if bad in text]
    return problems


def report_findings(findings):
    """print one line per finding and their count; the hunt's exit code (1 with any finding)"""
    for f in findings:
        print('FINDING: ' + f)
    print('%d findings' % len(findings))
    return 1 if findings else 0
