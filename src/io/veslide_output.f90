!> The result file at the edge: provenance written into it, and its atomic publication.
!>
!> A run takes its output with an advisory lock (`OUT.lock`: a second run on the same output is
!> refused while the first lives), writes to `OUT.part` and publishes it under `OUT` only when
!> complete: with link(2) then unlink(2), which fails if `OUT` appeared meanwhile (so two runs never
!> silently replace each other's result), or with rename(2) when overwriting was asked. A failed
!> run removes its part file and leaves any earlier result untouched; a killed study leaves its
!> part file, from which the same command resumes.
module veslide_output
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error, io_error
    use veslide_hdf5, only: h5file_t, hdf5_library_version
    use veslide_device, only: device_enabled, device_emulated, device_count, device_info_t, device_info
    use veslide_version, only: version_string, compiler_string, compiler_flags, git_revision, utc_timestamp
    use veslide_system, only: path_kind, PATH_MISSING, PATH_REGULAR, PATH_DIRECTORY, lock_file, unlock_file, LOCK_BUSY, &
                              last_system_error, rename_file, link_file, remove_file, process_id
    implicit none
    private
    public :: prepare_output, release_output, commit_output, discard_output, write_provenance, process_id

contains


    !> Check that the result can be written, before any work, and take the output: refuses an
    !> existing file unless `overwrite` (and anything but a regular file always), and refuses while
    !> another run holds the output's lock (`OUT.lock`, an advisory lock that dies with its process).
    !> The run writes to `tmp` = `OUT.part`; a part file left by a killed run is kept (a study
    !> resumes from it). `lock` is released by release_output.
    subroutine prepare_output(path, overwrite, tmp, lock, error)
        character(len=*), intent(in) :: path
        logical, intent(in) :: overwrite
        character(len=:), allocatable, intent(out) :: tmp
        !> the lock's descriptor (>= 0) while the output is taken
        integer, intent(out) :: lock
        type(error_t), allocatable, intent(out) :: error
        integer :: u, stat
        character(len=512) :: msg
        lock = -1
        select case (path_kind(path))
        case (PATH_MISSING)
        case (PATH_REGULAR)
            if (.not. overwrite) then
                call fatal_error(error, "veslide: &output file '"//path//"' exists; "// &
                    "set &output overwrite = .true. or pass --overwrite to replace it"); return
            end if
        case (PATH_DIRECTORY)
            call fatal_error(error, "veslide: &output file '"//path//"' is a directory; give a file name"); return
        case default
            call fatal_error(error, "veslide: &output file '"//path//"' exists and is not a regular file"// &
                " (a FIFO, device or socket); veslide replaces only regular files"); return
        end select
        tmp = path//'.part'
        if (path_kind(tmp) /= PATH_MISSING .and. path_kind(tmp) /= PATH_REGULAR) then
            call fatal_error(error, "veslide: '"//tmp//"' (the output's part file) is not a regular file"); return
        end if
        lock = lock_file(path//'.lock')
        if (lock == LOCK_BUSY) then
            call fatal_error(error, "veslide: another veslide run is writing &output file '"//path// &
                "' (it holds '"//path//".lock'); wait for it or choose another output"); return
        else if (lock < 0) then
            call io_error(error, "veslide: &output file '"//path//"' cannot be written: cannot create or lock '"// &
                             path//".lock' in its directory: "//last_system_error()); return
        end if
        if (path_kind(tmp) == PATH_MISSING) then
            open (newunit=u, file=tmp, status='new', action='write', iostat=stat, iomsg=msg)
            if (stat == 0) close (u, status='delete')
        else
            open (newunit=u, file=tmp, status='old', action='readwrite', iostat=stat, iomsg=msg)
            if (stat == 0) close (u)
        end if
        if (stat /= 0) then
            call release_output(lock, path)
            call io_error(error, "veslide: &output file '"//path//"' cannot be written: "//trim(msg)); return
        end if
    end subroutine prepare_output

    !> Give the output back: the lock released and its file removed
    subroutine release_output(lock, path)
        integer, intent(inout) :: lock
        character(len=*), intent(in) :: path
        if (lock < 0) return
        call remove_file(path//'.lock')
        call unlock_file(lock)
        lock = -1
    end subroutine release_output

    !> Publish the finished temporary file under its final name: without replacing anything
    !> (link + unlink) unless `overwrite` (rename)
    subroutine commit_output(tmp, path, overwrite, error)
        character(len=*), intent(in) :: tmp, path
        logical, intent(in) :: overwrite
        type(error_t), allocatable, intent(out) :: error
        if (path_kind(path) /= PATH_MISSING .and. path_kind(path) /= PATH_REGULAR) then
            call io_error(error, "veslide: &output file '"//path//"' is no longer a regular file; the result"// &
                " stays in '"//tmp//"'"); return
        end if
        if (overwrite) then
            if (.not. rename_file(tmp, path)) &
                call io_error(error, "veslide: cannot rename '"//tmp//"' to '"//path//"'")
            return
        end if
        if (.not. link_file(tmp, path)) then
            call io_error(error, "veslide: &output file '"//path//"' cannot be published (it appeared while"// &
                " this run worked, or the directory refuses links); the result stays in '"//tmp//"'")
            return
        end if
        call remove_file(tmp)
    end subroutine commit_output

    !> Remove a temporary file, if present
    subroutine discard_output(tmp)
        character(len=*), intent(in) :: tmp
        call remove_file(tmp)
    end subroutine discard_output

    !> Root attributes of provenance, and the input text as /input/namelist. A single case
    !> records its `seed`; a study (`study` present and true) the list of its `seeds`.
    subroutine write_provenance(f, input_path, input_text, seeds, error, study, preparation)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: input_path, input_text
        integer(i8), intent(in) :: seeds(:)
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: study
        !> a height file's record of its preparation (`/input/surface_preparation` when not '')
        character(len=*), intent(in), optional :: preparation
        logical :: study_
        study_ = .false.; if (present(study)) study_ = study
        call f%writeattr('/', 'veslide_version', version_string(), error); if (allocated(error)) return
        call f%writeattr('/', 'git_revision', git_revision(), error); if (allocated(error)) return
        call f%writeattr('/', 'compiler', compiler_string(), error); if (allocated(error)) return
        call f%writeattr('/', 'compiler_options', compiler_flags(), error); if (allocated(error)) return
        call f%writeattr('/', 'hdf5_version', hdf5_library_version(), error); if (allocated(error)) return
        call f%writeattr('/', 'created', utc_timestamp(), error); if (allocated(error)) return
        if (study_) then
            call f%writeattr('/', 'seeds', seeds, error)
        else
            call f%writeattr('/', 'seed', seeds(1), error)
        end if
        if (allocated(error)) return
        call f%writeattr('/', 'input_file', input_path, error); if (allocated(error)) return
        call write_device_provenance(f, error); if (allocated(error)) return
        call f%write('/input/namelist', input_text, error); if (allocated(error)) return
        call f%writeattr('/input/namelist', 'units', '-', error); if (allocated(error)) return
        if (present(preparation)) then
            if (len(preparation) > 0) then
                call f%write('/input/surface_preparation', preparation, error); if (allocated(error)) return
                call f%writeattr('/input/surface_preparation', 'units', '-', error)
            end if
        end if
    end subroutine write_provenance

    !> The build's device support ('none', 'cuda' or 'cuda-emulated'), and the device this process
    !> uses when one is visible: name, memory, CUDA driver and runtime versions, compute
    !> capability (root attributes; which cases ran on it: each /scalars group's `device`)
    subroutine write_device_provenance(f, error)
        type(h5file_t), intent(inout) :: f
        type(error_t), allocatable, intent(out) :: error
        type(device_info_t) :: info
        type(error_t), allocatable :: none
        if (.not. device_enabled) then
            call f%writeattr('/', 'device_support', 'none', error); return
        end if
        call f%writeattr('/', 'device_support', trim(merge('cuda-emulated', 'cuda         ', device_emulated())), error)
        if (allocated(error)) return
        if (device_count() == 0) return
        call device_info(info, none)
        if (allocated(none)) return
        call f%writeattr('/', 'device_name', info%name, error); if (allocated(error)) return
        call f%writeattr('/', 'device_memory_bytes', info%memory_bytes, error); if (allocated(error)) return
        call f%writeattr('/', 'cuda_driver_version', version_text(info%driver_version), error)
        if (allocated(error)) return
        call f%writeattr('/', 'cuda_runtime_version', version_text(info%runtime_version), error)
        if (allocated(error)) return
        call f%writeattr('/', 'device_compute_capability', version_text(100*info%compute_capability), error)
    contains
        !> 12030 -> '12.3'
        function version_text(v) result(t)
            integer, intent(in) :: v
            character(len=:), allocatable :: t
            character(len=16) :: b
            write (b, '(i0,".",i0)') v/1000, modulo(v, 1000)/10
            t = trim(b)
        end function version_text
    end subroutine write_device_provenance

end module veslide_output
