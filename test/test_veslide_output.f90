!> The result file at the edge: refusal to replace, publication without replacing, clean-up of
!> the part file, provenance and the version
module test_veslide_output
    use veslide_kinds, only: i8
    use veslide_error, only: fatal_error
    use veslide_hdf5, only: h5file_t
    use veslide_output, only: prepare_output, release_output, commit_output, discard_output, write_provenance
    use veslide_version, only: veslide_version_number
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use test_support, only: unique_name, write_text, remove
    implicit none
    private
    public :: collect_output

contains

    subroutine collect_output(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("output-exists-not-overwritten", test_output_exists), &
            new_unittest("output-unwritable", test_output_unwritable), &
            new_unittest("publish-never-replaces", test_publish_no_replace), &
            new_unittest("publish-with-overwrite-replaces", test_publish_overwrite), &
            new_unittest("provenance-attributes", test_provenance), &
            new_unittest("version-matches-fpm-toml", test_version) &
            ]
    end subroutine collect_output

    function first_line(path) result(line)
        character(len=*), intent(in) :: path
        character(len=32) :: line
        integer :: u
        open (newunit=u, file=path, status='old'); read (u, '(a)') line; close (u)
    end function first_line


    !> An existing result is never replaced unless asked, and is left untouched
    subroutine test_output_exists(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: path, tmp
        integer :: lock
        type(error_t), allocatable :: e
        path = unique_name('exists.h5')
        call write_text(path, 'earlier result')
        call prepare_output(path, .false., tmp, lock, e)
        call check(error, allocated(e), "existing output accepted"); if (allocated(error)) return
        call check(error, index(e%message, "overwrite") > 0, "message does not say how: "//e%message)
        if (allocated(error)) return
        call check(error, first_line(path) == 'earlier result', "earlier result changed")
        call remove(path)
    end subroutine test_output_exists

    subroutine test_output_unwritable(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: tmp
        type(error_t), allocatable :: e
        integer :: lock
        call prepare_output('/nonexistent-dir/out.h5', .true., tmp, lock, e)
        call check(error, allocated(e), "unwritable path accepted"); if (allocated(error)) return
        call check(error, index(e%message, "/nonexistent-dir/out.h5") > 0, "message lacks the path: "//e%message)
    end subroutine test_output_unwritable

    !> A result that appears while a run works (another run finished first) is not replaced: the
    !> publication fails, says so, and the run's own result stays in its part file
    subroutine test_publish_no_replace(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: path, tmp
        integer :: lock
        type(error_t), allocatable :: e
        logical :: exists
        path = unique_name('race.h5')
        call prepare_output(path, .false., tmp, lock, error); if (allocated(error)) return
        call write_text(tmp, 'this run')
        call write_text(path, 'the other run')
        call commit_output(tmp, path, .false., e)
        call check(error, allocated(e), "a result that appeared meanwhile was replaced"); if (allocated(error)) return
        call check(error, index(e%message, tmp) > 0, "message does not name the part file: "//e%message)
        if (allocated(error)) return
        call check(error, first_line(path) == 'the other run', "the other run's result changed")
        if (allocated(error)) return
        inquire (file=tmp, exist=exists)
        call check(error, exists, "this run's result was lost")
        call remove(path); call discard_output(tmp); call release_output(lock, path)
    end subroutine test_publish_no_replace

    subroutine test_publish_overwrite(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: path, tmp
        integer :: lock
        logical :: exists
        path = unique_name('replace.h5')
        call write_text(path, 'old')
        call prepare_output(path, .true., tmp, lock, error); if (allocated(error)) return
        call write_text(tmp, 'new')
        call commit_output(tmp, path, .true., error); if (allocated(error)) return
        call check(error, first_line(path) == 'new', "not replaced"); if (allocated(error)) return
        inquire (file=tmp, exist=exists)
        call check(error, .not. exists, "part file left behind")
        call release_output(lock, path)
        call remove(path)
    end subroutine test_publish_overwrite

    subroutine test_provenance(error)
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        character(len=:), allocatable :: path, text, version
        path = unique_name('prov.h5')
        call f%open(path, 'w', error); if (allocated(error)) return
        call write_provenance(f, 'in.nml', "&grid nx = 8 /", [7_i8], error); if (allocated(error)) return
        call f%close(error); if (allocated(error)) return
        call f%open(path, 'r', error); if (allocated(error)) return
        call check(error, f%attr_exists('/', 'git_revision') .and. f%attr_exists('/', 'compiler') .and. &
                   f%attr_exists('/', 'seed') .and. f%attr_exists('/', 'hdf5_version') .and. &
                   f%attr_exists('/', 'created') .and. f%attr_exists('/', 'compiler_options'), "provenance attributes")
        if (allocated(error)) return
        call f%read_text('/input/namelist', text, error); if (allocated(error)) return
        call check(error, text == "&grid nx = 8 /", "input text"); if (allocated(error)) return
        call f%read_attr_text('/', 'veslide_version', version, error); if (allocated(error)) return
        call check(error, version == veslide_version_number, "version attribute")
        call f%close()
        call remove(path)
    end subroutine test_provenance

    subroutine test_version(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=256) :: line
        integer :: u, stat
        open (newunit=u, file='fpm.toml', status='old', action='read', iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, "fpm.toml not found (tests run from the project root)"); return
        end if
        do
            read (u, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, 'version') == 1) exit
        end do
        close (u)
        call check(error, index(line, '"'//veslide_version_number//'"') > 0, &
                   "fpm.toml says "//trim(line)//", the code says "//veslide_version_number)
    end subroutine test_version

end module test_veslide_output
